// MeshShape: the Bullet-facing shape over a shared ADB-tree.
#include "adb/bullet/mesh_shape.h"

#include <cmath>
#include <string>

#include "adb/core/box_query.h"
#include "conversions.h"

namespace adb {
namespace {

using detail::fromBt;
using detail::toBt;

// The winding's sign from the signed volume (divergence theorem), taken about the box centre
// so that a mesh far from the origin does not lose it to cancellation.
int facingOf(const TriangleMesh& mesh, const MassProperties& mass) {
  if (!mass.closed) return 0;
  const Vec3 c = mesh.bounds().center();
  double volume6 = 0.0;
  for (const Triangle& t : mesh.triangles()) {
    const Vec3 a = mesh.vertices()[t[0]] - c, b = mesh.vertices()[t[1]] - c,
               d = mesh.vertices()[t[2]] - c;
    volume6 += a.dot(b.cross(d));
  }
  return volume6 > 0.0 ? 1 : volume6 < 0.0 ? -1 : 0;
}

}  // namespace

std::shared_ptr<const MeshData> MeshData::build(TriangleMesh mesh, const BuildSettings& settings) {
  AdbTree tree(mesh, settings);
  MassProperties mass = computeMassProperties(mesh);
  const int facing = facingOf(mesh, mass);
  return std::make_shared<const MeshData>(
      MeshData{std::move(mesh), std::move(tree), mass, facing});
}

MeshShape::MeshShape(std::shared_ptr<const MeshData> data) : m_data(std::move(data)) {
  m_shapeType = CUSTOM_CONCAVE_SHAPE_TYPE;
}

void MeshShape::getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const {
  // The root box (local to the tree) moved to mesh coordinates, then to the world: the
  // centre maps, the half extents map through |R|.
  const Node& root = tree().root();
  const Vec3 centre = 0.5 * (root.boxLo() + root.boxHi()) + tree().origin();
  const btVector3 half = toBt(0.5 * (root.boxHi() - root.boxLo())) +
                         btVector3(getMargin(), getMargin(), getMargin());
  const btMatrix3x3 abs = t.getBasis().absolute();
  const btVector3 c = t(toBt(centre));
  const btVector3 e(abs[0].dot(half), abs[1].dot(half), abs[2].dot(half));
  aabbMin = c - e;
  aabbMax = c + e;
}

void MeshShape::setLocalScaling(const btVector3& scaling) {
  const Vec3 s = fromBt(scaling);
  if (!s.allFinite() || (s.array() <= 0.0).any()) {
    throw SettingsError("MeshShape::setLocalScaling: the scaling must be positive and finite");
  }
  m_scaling = scaling;
  if (s == Vec3::Ones()) {
    m_scaled.reset();
    return;
  }
  // A scaled mesh needs its own tree: boxes, slabs and cell counts all change with it.
  std::vector<Vec3> v = m_data->mesh.vertices();
  for (Vec3& x : v) x = x.cwiseProduct(s);
  m_scaled = MeshData::build(TriangleMesh(std::move(v), m_data->mesh.triangles(),
                                          m_data->mesh.name() + " (scaled)"),
                             m_data->tree.settings());
}

void MeshShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const {
  // Bullet reads the result as the diagonal of the inertia tensor in the shape's frame: exact
  // when that frame is the principal frame (see principalTransform), the best diagonal
  // otherwise.
  inertia = toBt(data().mass.inertia.diagonal()) * mass;
}

btTransform MeshShape::principalTransform() const {
  const MassProperties& m = data().mass;
  const Mat3& r = m.principalAxes;
  const btMatrix3x3 basis(static_cast<btScalar>(r(0, 0)), static_cast<btScalar>(r(0, 1)),
                          static_cast<btScalar>(r(0, 2)), static_cast<btScalar>(r(1, 0)),
                          static_cast<btScalar>(r(1, 1)), static_cast<btScalar>(r(1, 2)),
                          static_cast<btScalar>(r(2, 0)), static_cast<btScalar>(r(2, 1)),
                          static_cast<btScalar>(r(2, 2)));
  return btTransform(basis, toBt(m.centerOfMass));
}

void MeshShape::processAllTriangles(btTriangleCallback* callback, const btVector3& aabbMin,
                                    const btVector3& aabbMax) const {
  const AdbTree& t = tree();
  const auto& verts = t.localVertices();
  forEachTriangleNear(t, Aabb{fromBt(aabbMin), fromBt(aabbMax)}, [&](std::uint32_t i) {
    btVector3 corners[3];
    for (int k = 0; k < 3; ++k) corners[k] = toBt(verts[t.triangles()[i][k]] + t.origin());
    callback->processTriangle(corners, 0, static_cast<int>(t.meshTriangle(i)));
  });
}

}  // namespace adb
