#include "body_shapes.h"

#include <BulletCollision/Gimpact/btGImpactShape.h>

#include <cmath>

#include "adb/support/mesh_generators.h"
#include "adb/io/mesh_file.h"
#include "adb/io/message_text.h"
#include "adb/scene/scene_file.h"
#include "adb/scene/scene_models.h"
#include "adb/bullet/conversions.h"

namespace adb::scene::detail {
namespace {

// A plane is drawn as a square this wide: larger than any gallery scene.
constexpr double kPlaneDisplaySize = 12.0;

TriangleMesh planeDisplay(const ShapeSpec& s) {
  const Mat3 toNormal =
      Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), s.normal).toRotationMatrix();
  return gen::transformed(gen::makeFlatGrid(kPlaneDisplaySize, kPlaneDisplaySize, 1, 1),
                          Pose{toNormal, s.offset * s.normal});
}

// Bullet's capsule lies along y with `height` between the caps' centres.
TriangleMesh capsuleDisplay(const ShapeSpec& s) {
  const Mat3 zToY = Eigen::AngleAxisd(-0.5 * M_PI, Vec3::UnitX()).toRotationMatrix();
  const TriangleMesh cap = gen::makeSphere(s.radius, 3);
  std::vector<TriangleMesh> parts = {
      gen::transformed(cap, Pose{Mat3::Identity(), Vec3(0, 0.5 * s.height, 0)}),
      gen::transformed(cap, Pose{Mat3::Identity(), Vec3(0, -0.5 * s.height, 0)})};
  if (s.height > 0) {
    parts.push_back(gen::transformed(gen::makeCylinder(s.radius, s.height, 24), Pose{zToY, {}}));
  }
  return gen::merge(parts, s.name);
}

TriangleMesh recentred(const TriangleMesh& mesh) {
  const Vec3 centre = mesh.bounds().center();
  return gen::transformed(mesh, Pose{Mat3::Identity(), -centre});
}

// Scaled about its box's centre so that its largest extent is `size`.
TriangleMesh sizedTo(const TriangleMesh& mesh, double size) {
  const Vec3 centre = mesh.bounds().center();
  const double extent = mesh.bounds().extent().maxCoeff();
  const double k = extent > 0 ? size / extent : 1.0;
  std::vector<Vec3> vertices;
  vertices.reserve(mesh.vertices().size());
  for (const Vec3& v : mesh.vertices()) vertices.push_back((v - centre) * k);
  return TriangleMesh(std::move(vertices), mesh.triangles(), mesh.name());
}

// A mesh shape's triangles: its file's or the mesh given in code, sized or scaled and
// recentred as the shape asks.
TriangleMesh meshOf(const ShapeSpec& s) {
  TriangleMesh mesh = s.given ? *s.given : io::loadMesh(s.file.string());
  if (s.size > 0) return sizedTo(mesh, s.size);
  if (s.scale != 1.0) mesh = gen::transformed(mesh, Pose{s.scale * Mat3::Identity(), Vec3::Zero()});
  return s.recentre ? recentred(mesh) : mesh;
}

// A primitive's display mesh: its triangles for pictures.
TriangleMesh primitiveDisplay(const ShapeSpec& s) {
  switch (s.kind) {
    case ShapeSpec::Kind::Box: return gen::makeBox(s.halfExtents, 1);
    case ShapeSpec::Kind::Sphere: return gen::makeSphere(s.radius, 4);
    case ShapeSpec::Kind::Capsule: return capsuleDisplay(s);
    default: return planeDisplay(s);
  }
}

std::unique_ptr<btCollisionShape> primitiveShape(const ShapeSpec& s) {
  const auto r = static_cast<btScalar>(s.radius);
  switch (s.kind) {
    case ShapeSpec::Kind::Box: return std::make_unique<btBoxShape>(toBt(s.halfExtents));
    case ShapeSpec::Kind::Sphere: return std::make_unique<btSphereShape>(r);
    case ShapeSpec::Kind::Capsule:
      return std::make_unique<btCapsuleShape>(r, static_cast<btScalar>(s.height));
    default:
      return std::make_unique<btStaticPlaneShape>(toBt(s.normal), static_cast<btScalar>(s.offset));
  }
}

}  // namespace

BodyShapes::BodyShapes(const Scene& scene, Backend backend, ConvexShapeMaker convex)
    : m_scene(scene), m_backend(backend), m_convex(std::move(convex)) {}

// The mesh of a mesh or generated shape, read or generated once. Its faults are the scene's:
// they name the shape.
const TriangleMesh& BodyShapes::sourceMesh(std::size_t shape) {
  auto it = m_sources.find(shape);
  if (it != m_sources.end()) return it->second;
  const ShapeSpec& s = m_scene.shapes[shape];
  const std::string file = m_scene.file.empty() ? "scene" : m_scene.file.string();
  try {
    TriangleMesh mesh = s.kind == ShapeSpec::Kind::Generated ? generatedMesh(s) : meshOf(s);
    return m_sources.emplace(shape, std::move(mesh)).first->second;
  } catch (const std::exception& e) {
    const std::string where = "shapes." + io::excerpt(s.name, 60);
    throw SceneError(file, where + (s.kind == ShapeSpec::Kind::Mesh ? ".file" : ""), e.what());
  }
}

std::shared_ptr<const MeshData> BodyShapes::meshData(std::size_t shape, ShapeFrame frame) {
  const auto key = std::make_pair(shape, frame);
  auto it = m_data.find(key);
  if (it != m_data.end()) return it->second;
  try {
    auto data = MeshData::build(sourceMesh(shape), BuildSettings{}, frame);
    return m_data.emplace(key, std::move(data)).first->second;
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    throw SceneError(m_scene.file.empty() ? "scene" : m_scene.file.string(),
                     "shapes." + m_scene.shapes[shape].name, e.what());
  }
}

btCollisionShape* BodyShapes::keep(std::unique_ptr<btCollisionShape> shape) {
  m_shapes.push_back(std::move(shape));
  return m_shapes.back().get();
}

// adb's backends give every body its own MeshShape over the shared MeshData; the others share
// one shape per mesh: GImpact's, or the convex backend's decomposition, for moving bodies, and
// Bullet's BVH mesh for static ones (as Bullet users build static meshes).
btCollisionShape* BodyShapes::meshShape(std::size_t shape,
                                        const std::shared_ptr<const MeshData>& data,
                                        BodySpec::Kind kind) {
  if (usesAdbShapes(m_backend)) return keep(std::make_unique<MeshShape>(data));
  const bool moving = kind != BodySpec::Kind::Static;
  const auto key = std::make_pair(shape, moving ? ShapeFrame::Principal : ShapeFrame::Mesh);
  auto it = m_shared.find(key);
  if (it != m_shared.end()) return it->second;
  btCollisionShape* made = nullptr;
  if (moving && m_backend == Backend::Convex) {
    std::vector<std::unique_ptr<btCollisionShape>> parts = m_convex(*data);
    if (parts.empty()) throw std::logic_error("the convex shape maker returned no shape");
    for (auto& part : parts) made = keep(std::move(part));  // the body's shape comes last
    m_shared.emplace(key, made);
    return made;
  }
  m_arrays.push_back(std::make_unique<TriangleArrays>(data->mesh));
  if (moving) {
    auto gimpact = std::make_unique<btGImpactMeshShape>(m_arrays.back()->array.get());
    gimpact->updateBound();
    made = keep(std::move(gimpact));
  } else {
    made = keep(std::make_unique<btBvhTriangleMeshShape>(m_arrays.back()->array.get(), true));
  }
  m_shared.emplace(key, made);
  return made;
}

// A shape per body (Bullet may scale each), the display mesh per shape.
BodyShape BodyShapes::primitive(std::size_t shape) {
  const ShapeSpec& s = m_scene.shapes[shape];
  BodyShape out;
  out.shape = keep(primitiveShape(s));
  auto it = m_displays.find(shape);
  if (it == m_displays.end()) it = m_displays.emplace(shape, primitiveDisplay(s)).first;
  out.display = &it->second;
  return out;
}

BodyShape BodyShapes::make(const BodySpec& body) {
  const ShapeSpec& spec = m_scene.shapes[body.shape];
  if (spec.kind != ShapeSpec::Kind::Mesh && spec.kind != ShapeSpec::Kind::Generated) {
    return primitive(body.shape);
  }
  // A dynamic body's shape is in its principal frame: Bullet takes the shape's origin for the
  // centre of mass and its axes for the principal axes.
  const ShapeFrame frame =
      body.kind == BodySpec::Kind::Dynamic ? ShapeFrame::Principal : ShapeFrame::Mesh;
  BodyShape out;
  out.mesh = meshData(body.shape, frame);
  out.shape = meshShape(body.shape, out.mesh, body.kind);
  out.meshFromShape = out.mesh->meshFromShape;
  out.display = &out.mesh->mesh;
  m_triangles += out.mesh->mesh.triangleCount();
  return out;
}

}  // namespace adb::scene::detail
