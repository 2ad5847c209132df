// The AABB hierarchy of an AdbTree and its per-node surface statistics.
//
// Split rule: the longest axis of the centroid bounds, at the median centroid (nth_element).
// Why the object median rather than SAH: (1) the tree is balanced, so its depth is
// ceil(log2(n / leaf)) and every leaf sits at nearly the same depth — the probability model's
// lower bound LB = (dA + dB) / (dmaxA + dmaxB) (paper §3.6.3) reads depth as "how flat is
// this polygon set", which only means the same thing everywhere in a balanced tree; (2) the
// build is O(n log n) with small constants (1M triangles well under a second); (3) it is the
// same family as the restricted boxtree the paper built on. Degenerate input (all centroids
// equal) still splits in halves, so the depth bound holds for any mesh.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <numeric>

#include "tree_builder.h"

namespace adb::detail {
namespace {

struct BuildItem {
  std::uint32_t node;
  std::uint32_t begin, end;  // range in the permutation
  int depth;
};

// Float box that contains the double box: rounded outward, so no query can miss a triangle
// because of the conversion.
void storeBox(Node& n, const Aabb& box) {
  // AdbTree's validation bounds coordinates (1e150) and extents (1e12), so local boxes are
  // finite and far inside float's range: no inf or NaN can reach a stored box.
  assert(box.lo.allFinite() && box.hi.allFinite());
  for (int k = 0; k < 3; ++k) {
    float lo = static_cast<float>(box.lo[k]);
    float hi = static_cast<float>(box.hi[k]);
    if (static_cast<double>(lo) > box.lo[k]) lo = std::nextafter(lo, -INFINITY);
    if (static_cast<double>(hi) < box.hi[k]) hi = std::nextafter(hi, INFINITY);
    n.lo[k] = lo;
    n.hi[k] = hi;
  }
}

}  // namespace

void buildHierarchy(AdbTree& tree, const TriangleMesh& mesh, int maxLeafTriangles) {
  auto& nodes = TreeBuilderAccess::nodes(tree);
  auto& verts = TreeBuilderAccess::vertices(tree);
  const Vec3 origin = mesh.bounds().center();
  TreeBuilderAccess::origin(tree) = origin;
  verts.resize(mesh.vertices().size());
  for (std::size_t i = 0; i < verts.size(); ++i) verts[i] = mesh.vertices()[i] - origin;

  const auto& tris = mesh.triangles();
  const std::size_t n = tris.size();
  std::vector<Aabb> triBox(n);
  std::vector<Vec3> centroid(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) triBox[i].grow(verts[tris[i][k]]);
    centroid[i] = triBox[i].center();  // box centre: cheaper than the mean, same ordering role
  }
  std::vector<std::uint32_t> perm(n);
  std::iota(perm.begin(), perm.end(), 0u);

  nodes.clear();
  nodes.reserve(2 * (n / static_cast<std::size_t>(maxLeafTriangles) + 1));
  nodes.push_back(Node{});
  std::vector<BuildItem> stack{{0u, 0u, static_cast<std::uint32_t>(n), 0}};
  int maxDepth = 0;
  while (!stack.empty()) {
    const BuildItem item = stack.back();
    stack.pop_back();
    Aabb box, cbox;
    for (std::uint32_t i = item.begin; i < item.end; ++i) {
      box.grow(triBox[perm[i]]);
      cbox.grow(centroid[perm[i]]);
    }
    storeBox(nodes[item.node], box);
    nodes[item.node].pc = 0.0f;
    const std::uint32_t count = item.end - item.begin;
    maxDepth = std::max(maxDepth, item.depth);
    if (count <= static_cast<std::uint32_t>(maxLeafTriangles)) {
      nodes[item.node].packed = (item.begin << 4) | count;
      continue;
    }
    int axis = 0;
    const Vec3 ext = cbox.extent();
    if (ext.y() > ext[axis]) axis = 1;
    if (ext.z() > ext[axis]) axis = 2;
    const std::uint32_t mid = item.begin + count / 2;
    std::nth_element(perm.begin() + item.begin, perm.begin() + mid, perm.begin() + item.end,
                     [&](std::uint32_t a, std::uint32_t b) {
                       return centroid[a][axis] < centroid[b][axis];
                     });
    const auto first = static_cast<std::uint32_t>(nodes.size());
    nodes.push_back(Node{});
    nodes.push_back(Node{});
    nodes[item.node].packed = first << 4;
    stack.push_back({first + 1, mid, item.end, item.depth + 1});
    stack.push_back({first, item.begin, mid, item.depth + 1});
  }
  TreeBuilderAccess::maxDepth(tree) = maxDepth;

  auto& outTris = TreeBuilderAccess::triangles(tree);
  auto& meshTri = TreeBuilderAccess::meshTriangle(tree);
  outTris.resize(n);
  meshTri.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    outTris[i] = tris[perm[i]];
    meshTri[i] = perm[i];
  }
}

void computeSurfaces(AdbTree& tree) {
  const auto& nodes = tree.nodes();
  auto& surf = TreeBuilderAccess::surfaces(tree);
  surf.assign(nodes.size(), NodeSurface{});
  const auto& verts = tree.localVertices();
  const auto& tris = tree.triangles();
  std::vector<Vec3> areaNormal(nodes.size(), Vec3::Zero());  // sum a_i n_i
  std::vector<Vec3> areaCentroid(nodes.size(), Vec3::Zero());
  std::vector<double> area(nodes.size(), 0.0);
  // Children always have larger indices than their parent: a reverse sweep is bottom-up.
  for (std::size_t i = nodes.size(); i-- > 0;) {
    const Node& node = nodes[i];
    if (node.isLeaf()) {
      for (std::uint32_t t = node.firstTriangle(); t < node.firstTriangle() + node.triangleCount();
           ++t) {
        const Vec3 &a = verts[tris[t][0]], &b = verts[tris[t][1]], &c = verts[tris[t][2]];
        const Vec3 cross = (b - a).cross(c - a);  // |cross| = 2 area; direction = normal
        const double triArea = 0.5 * cross.norm();
        areaNormal[i] += 0.5 * cross;
        areaCentroid[i] += triArea * (a + b + c) / 3.0;
        area[i] += triArea;
      }
    } else {
      for (std::uint32_t c = node.firstChild(); c < node.firstChild() + 2; ++c) {
        areaNormal[i] += areaNormal[c];
        areaCentroid[i] += areaCentroid[c];
        area[i] += area[c];
      }
    }
    NodeSurface& s = surf[i];
    s.area = static_cast<float>(area[i]);
    const double len = areaNormal[i].norm();
    const Vec3 normal = len > 0.0 ? Vec3(areaNormal[i] / len) : Vec3::Zero();
    // Degenerate-only nodes have no area: use the box centre as their centroid.
    const Vec3 centroid = area[i] > 0.0 ? Vec3(areaCentroid[i] / area[i])
                                        : Vec3(0.5 * (node.boxLo() + node.boxHi()));
    for (int k = 0; k < 3; ++k) {
      s.normal[k] = static_cast<float>(normal[k]);
      s.centroid[k] = static_cast<float>(centroid[k]);
    }
    s.coherence = area[i] > 0.0 ? static_cast<float>(std::min(1.0, len / area[i])) : 0.0f;
  }
}

namespace {

// The slab normal of a node: its mean surface normal where the normals agree enough to make a
// thin slab, else the box's thinnest axis (a closed or strongly curved patch).
Vec3 slabNormal(const Node& node, const NodeSurface& surface) {
  // Below this coherence (|sum a n| / sum a) the mean normal is mostly cancellation.
  constexpr float kMinCoherence = 0.3f;
  if (surface.coherence >= kMinCoherence) {
    return Vec3(surface.normal[0], surface.normal[1], surface.normal[2]);
  }
  const Vec3 e = node.boxHi() - node.boxLo();
  int axis = 0;
  if (e.y() < e[axis]) axis = 1;
  if (e.z() < e[axis]) axis = 2;
  return Vec3::Unit(axis);
}

// Rounds a float up so that it is >= x (x >= 0).
float roundUp(double x) {
  float f = static_cast<float>(x);
  if (static_cast<double>(f) < x) f = std::nextafter(f, INFINITY);
  return f;
}

}  // namespace

void computeSlabs(AdbTree& tree) {
  const auto& nodes = tree.nodes();
  auto& dist = TreeBuilderAccess::distributions(tree);
  dist.resize(nodes.size());
  const auto ranges = triangleRanges(tree);
  const auto& verts = tree.localVertices();
  const auto& tris = tree.triangles();
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const NodeSurface& surface = tree.surfaces()[i];
    const Vec3 n = slabNormal(nodes[i], surface);
    // The stored (float) normal and offset are what the traversal reads: measure the width
    // against those, in double, and round it up, so the slab is conservative as stored.
    float normal[3];
    for (int k = 0; k < 3; ++k) normal[k] = static_cast<float>(n[k]);
    const Vec3 nf(normal[0], normal[1], normal[2]);
    const Vec3 c(surface.centroid[0], surface.centroid[1], surface.centroid[2]);
    const float offset = static_cast<float>(nf.dot(c));
    double width = 0.0;
    for (std::uint32_t t = ranges[i].first; t < ranges[i].second; ++t) {
      for (std::uint32_t v : tris[t]) width = std::max(width, std::abs(nf.dot(verts[v]) - offset));
    }
    NodeDistribution& d = dist[i];
    for (int k = 0; k < 3; ++k) d.normal[k] = normal[k];
    d.offset = offset;
    d.halfWidth = roundUp(width);
  }
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> triangleRanges(const AdbTree& tree) {
  const auto& nodes = tree.nodes();
  std::vector<std::pair<std::uint32_t, std::uint32_t>> range(nodes.size());
  for (std::size_t i = nodes.size(); i-- > 0;) {
    const Node& node = nodes[i];
    if (node.isLeaf()) {
      range[i] = {node.firstTriangle(), node.firstTriangle() + node.triangleCount()};
    } else {
      range[i] = {range[node.firstChild()].first, range[node.firstChild() + 1].second};
    }
  }
  return range;
}

}  // namespace adb::detail
