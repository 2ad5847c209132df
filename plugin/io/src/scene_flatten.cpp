// flattenScene: depth-first over the node tree, one MeshInstance per (node, mesh) placement.
#include "scene_flatten.h"

#include <assimp/scene.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <limits>
#include <sstream>
#include <unordered_map>
#include <unordered_set>

#include "adb/io/mesh_file.h"

namespace adb::io::detail {
namespace {

using Mat4 = Eigen::Matrix4d;

// A node transform may be off the affine form by float rounding only; further than this in
// its bottom row it is projective, which no mesh format means (we refuse, not guess).
constexpr double kAffineTolerance = 1e-6;

Mat4 toDouble(const aiMatrix4x4& m) {
  Mat4 out;
  out << m.a1, m.a2, m.a3, m.a4,  //
      m.b1, m.b2, m.b3, m.b4,     //
      m.c1, m.c2, m.c3, m.c4,     //
      m.d1, m.d2, m.d3, m.d4;
  return out;
}

std::string meshLabel(const aiScene& scene, unsigned mesh) {
  std::string label = "assimp mesh " + std::to_string(mesh);
  if (mesh < scene.mNumMeshes && scene.mMeshes[mesh] != nullptr &&
      scene.mMeshes[mesh]->mName.length > 0) {
    label += " '" + std::string(scene.mMeshes[mesh]->mName.C_Str()) + "'";
  }
  return label;
}

// Welding key: the float bit patterns of a source position, with -0 read as +0 (x + 0.0f).
// Exact equality only: assimp's JoinIdenticalVertices would also merge positions up to 1e-5
// apart and, given a NaN, merges unrelated vertices into it (seen with assimp 5.2).
struct PositionKey {
  std::array<std::uint32_t, 3> bits;
  bool operator==(const PositionKey& o) const { return bits == o.bits; }
};
struct PositionKeyHash {
  std::size_t operator()(const PositionKey& k) const {
    std::size_t h = 1469598103934665603ull;
    for (std::uint32_t b : k.bits) h = (h ^ b) * 1099511628211ull;
    return h;
  }
};
PositionKey keyOf(const aiVector3D& p) {
  PositionKey key{};
  const float c[3] = {p.x + 0.0f, p.y + 0.0f, p.z + 0.0f};
  for (int i = 0; i < 3; ++i) std::memcpy(&key.bits[i], &c[i], sizeof(float));
  return key;
}

// linear * p + translation, leaving out the terms whose coefficient is exactly 0: the identity
// (or a translation) then keeps a NaN where the file has it, "(nan, 0, 0)", instead of
// spreading it to every coordinate through 0 * NaN.
Vec3 transform(const Eigen::Matrix3d& linear, const Vec3& translation, const aiVector3D& p) {
  const double in[3] = {p.x, p.y, p.z};
  Vec3 out = translation;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      if (linear(r, c) != 0.0) out[r] += linear(r, c) * in[c];
    }
  }
  return out;
}

// A node's name in a path; unnamed nodes (the root of a PLY, say) get a placeholder.
std::string nodeName(const aiNode& node) {
  return node.mName.length > 0 ? std::string(node.mName.C_Str()) : std::string("(unnamed)");
}

class Flattener {
 public:
  Flattener(const aiScene& scene, const std::string& file) : m_scene(scene), m_file(file) {}

  FlatScene run() {
    std::vector<bool> placed(m_scene.mNumMeshes, false);
    struct Pending {
      const aiNode* node;
      Mat4 parent;
      std::string parentPath;
    };
    std::vector<Pending> stack;
    if (m_scene.mRootNode != nullptr) stack.push_back({m_scene.mRootNode, Mat4::Identity(), ""});
    std::unordered_set<const aiNode*> seen;
    while (!stack.empty()) {
      const Pending p = std::move(stack.back());
      stack.pop_back();
      const aiNode& node = *p.node;
      const std::string path =
          p.parentPath.empty() ? nodeName(node) : p.parentPath + "/" + nodeName(node);
      // assimp's node graph is a tree; a node seen twice is a cycle (it would never end).
      if (!seen.insert(&node).second) {
        fail("node '" + path + "' is reached twice in the scene graph");
      }
      const Mat4 global = p.parent * toDouble(node.mTransformation);
      for (unsigned i = 0; i < node.mNumMeshes; ++i) {
        const unsigned mesh = node.mMeshes[i];
        if (mesh >= m_scene.mNumMeshes || m_scene.mMeshes[mesh] == nullptr) {
          fail("node '" + path + "' places mesh " + std::to_string(mesh) + ", but the file has " +
               std::to_string(m_scene.mNumMeshes) + " meshes");
        }
        placed[mesh] = true;
        place(mesh, global, path);
      }
      // Children pushed last-first, so they are visited in their order.
      for (unsigned c = node.mNumChildren; c-- > 0;) {
        if (node.mChildren[c] != nullptr) stack.push_back({node.mChildren[c], global, path});
      }
    }
    for (unsigned m = 0; m < m_scene.mNumMeshes; ++m) {
      if (!placed[m]) m_flat.unreferencedMeshes.push_back(m);
    }
    return std::move(m_flat);
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw MeshFileError(m_file + ": " + what);
  }

  void place(unsigned meshIndex, const Mat4& global, const std::string& path) {
    const aiMesh& mesh = *m_scene.mMeshes[meshIndex];
    const std::string label = meshLabel(m_scene, meshIndex);
    // Faces first: a mesh without triangles adds nothing (not even vertices).
    std::vector<Triangle> source;
    source.reserve(mesh.mNumFaces);
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices == 1) {
        ++m_flat.skippedPoints;
        continue;
      }
      if (face.mNumIndices == 2) {
        ++m_flat.skippedLines;
        continue;
      }
      if (face.mNumIndices != 3) {
        fail(label + ", face " + std::to_string(f) + " has " + std::to_string(face.mNumIndices) +
             " vertices after triangulation");
      }
      Triangle t{};
      for (unsigned k = 0; k < 3; ++k) {
        t[k] = face.mIndices[k];
        if (t[k] >= mesh.mNumVertices) {
          fail(label + ", face " + std::to_string(f) + " references vertex " +
               std::to_string(t[k]) + ", but the mesh has " + std::to_string(mesh.mNumVertices) +
               " vertices");
        }
      }
      source.push_back(t);
    }
    if (source.empty()) {
      ++m_flat.instancesWithoutTriangles;
      return;
    }
    if (mesh.mVertices == nullptr) fail(label + " has faces but no vertex positions");

    const Eigen::RowVector4d offAffine = global.row(3) - Eigen::RowVector4d(0, 0, 0, 1);
    if (offAffine.cwiseAbs().maxCoeff() > kAffineTolerance) {
      fail("node '" + path + "' has a projective transform (bottom row not 0 0 0 1)");
    }
    const Eigen::Matrix3d linear = global.topLeftCorner<3, 3>();
    const Vec3 translation = global.topRightCorner<3, 1>();

    const std::size_t first = m_flat.vertices.size();
    if (first + mesh.mNumVertices > std::numeric_limits<std::uint32_t>::max()) {
      fail("more than 2^32 - 1 vertices");
    }
    m_flat.instances.push_back({meshIndex, path, static_cast<std::uint32_t>(first)});
    std::vector<std::uint32_t> remap(mesh.mNumVertices);
    std::unordered_map<PositionKey, std::uint32_t, PositionKeyHash> welded;
    welded.reserve(mesh.mNumVertices);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D& p = mesh.mVertices[v];
      const auto [it, added] =
          welded.try_emplace(keyOf(p), static_cast<std::uint32_t>(m_flat.vertices.size()));
      remap[v] = it->second;
      if (added) {
        m_flat.vertices.push_back(transform(linear, translation, p));
        m_flat.sourceVertex.push_back(v);
      }
    }
    for (const Triangle& t : source) {
      m_flat.triangles.push_back({remap[t[0]], remap[t[1]], remap[t[2]]});
    }
  }

  const aiScene& m_scene;
  const std::string& m_file;
  FlatScene m_flat;
};

}  // namespace

FlatScene flattenScene(const aiScene& scene, const std::string& file) {
  return Flattener(scene, file).run();
}

std::string describeVertexOrigin(const aiScene& scene, const FlatScene& flat, std::size_t v) {
  // The instance whose range holds v: the last one starting at or before it.
  const auto it = std::upper_bound(
      flat.instances.begin(), flat.instances.end(), v,
      [](std::size_t vertex, const MeshInstance& inst) { return vertex < inst.firstVertex; });
  if (it == flat.instances.begin() || v >= flat.sourceVertex.size()) return "unknown origin";
  const MeshInstance& inst = *(it - 1);
  const std::uint32_t source = flat.sourceVertex[v];
  const aiVector3D& p = scene.mMeshes[inst.mesh]->mVertices[source];
  std::ostringstream os;
  os.precision(9);
  os << "vertex " << source << " of " << meshLabel(scene, inst.mesh) << " placed by node '"
     << inst.node << "', at (" << p.x << ", " << p.y << ", " << p.z
     << ") in the mesh's own coordinates";
  return os.str();
}

}  // namespace adb::io::detail
