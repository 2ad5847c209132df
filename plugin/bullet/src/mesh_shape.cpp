// MeshShape: the Bullet-facing shape over a shared ADB-tree.
#include "adb/bullet/mesh_shape.h"

#include <numeric>
#include <vector>

#include <BulletCollision/NarrowPhaseCollision/btRaycastCallback.h>

#include <cmath>
#include <sstream>
#include <string>

#include "adb/bullet/warnings.h"
#include "adb/core/box_query.h"
#include "conversions.h"

namespace adb {
namespace {


// The root of vertex v's part (union-find with path halving).
std::uint32_t partOf(std::vector<std::uint32_t>& parent, std::uint32_t v) {
  while (parent[v] != v) v = parent[v] = parent[parent[v]];
  return v;
}

// The winding's sign from the signed volume (divergence theorem), taken about the box centre
// so that a mesh far from the origin does not lose it to cancellation: per connected part,
// and 0 (two-sided) when the parts disagree. A room's shell faces inward and its furniture
// outward: one sign for the whole turned the floor's back to the bodies on it, and every
// contact with it was dropped as facing away (robot arms fell through; demos/scenes/
// robot_room.json).
int facingOf(const TriangleMesh& mesh, const MassProperties& mass) {
  if (!mass.closed) return 0;
  const Vec3 c = mesh.bounds().center();
  const std::size_t n = mesh.vertices().size();
  std::vector<std::uint32_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0u);
  for (const Triangle& t : mesh.triangles()) {
    for (int k = 1; k < 3; ++k) parent[partOf(parent, t[k])] = partOf(parent, t[0]);
  }
  std::vector<double> volume6(n, 0.0);  // per part, at its root
  for (const Triangle& t : mesh.triangles()) {
    const Vec3 a = mesh.vertices()[t[0]] - c, b = mesh.vertices()[t[1]] - c,
               d = mesh.vertices()[t[2]] - c;
    volume6[partOf(parent, t[0])] += a.dot(b.cross(d));
  }
  bool outward = false, inward = false;
  for (double v : volume6) {
    outward = outward || v > 0.0;
    inward = inward || v < 0.0;
  }
  return outward == inward ? 0 : outward ? 1 : -1;
}

// The principal frame in mesh coordinates: origin at the centre of mass, axes the principal
// axes. computeMassProperties promises det +1; a reflection would mirror the mesh and turn
// its winding inside out, so one is corrected here rather than trusted.
Pose principalPose(const MassProperties& mass) {
  Pose p{mass.principalAxes, mass.centerOfMass};
  if (p.rotation.determinant() < 0.0) p.rotation.col(2) = -p.rotation.col(2);
  return p;
}

// Builds the data of `mesh`, moved to its principal frame if asked; `meshFromShape` is where
// `mesh`'s own frame already is in the original coordinates (a scaled copy keeps its
// parent's).
std::shared_ptr<const MeshData> buildData(TriangleMesh mesh, const BuildSettings& settings,
                                          ShapeFrame frame, const Pose& meshFromShape) {
  MassProperties mass = computeMassProperties(mesh);
  // A proper rotation keeps the sign of the volume: the winding is read before moving.
  const int facing = facingOf(mesh, mass);
  Pose offset = meshFromShape;
  if (frame == ShapeFrame::Principal) {
    const Pose p = principalPose(mass);
    std::vector<Vec3> v = mesh.vertices();
    for (Vec3& x : v) x = p.rotation.transpose() * (x - p.translation);
    mesh = TriangleMesh(std::move(v), mesh.triangles(), mesh.name());
    // The mass properties are moved rather than recomputed: the centre is then exactly the
    // origin and the tensor exactly diagonal (a recomputation returns rounding noise, and
    // axes possibly turned by 180 degrees).
    mass.centerOfMass = Vec3::Zero();
    mass.inertia = mass.principalMoments.asDiagonal();
    mass.principalAxes = Mat3::Identity();
    offset = meshFromShape * p;
  }
  AdbTree tree(mesh, settings);
  return std::make_shared<const MeshData>(
      MeshData{std::move(mesh), std::move(tree), mass, facing, offset, {}});
}

}  // namespace

std::shared_ptr<const MeshData> MeshData::build(TriangleMesh mesh, const BuildSettings& settings,
                                                ShapeFrame frame) {
  return buildData(std::move(mesh), settings, frame, Pose{});
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
  // Everything that can throw comes first; the commit below is two no-throw assignments
  // (strong guarantee: a failed build leaves scaling, tree and data as they were).
  std::shared_ptr<const MeshData> scaled;
  if (s != Vec3::Ones()) {
    // A scaled mesh needs its own tree: boxes, slabs and cell counts all change with it. The
    // scale applies in the shape's frame, so the offset to the original mesh is the parent's.
    std::vector<Vec3> v = m_data->mesh.vertices();
    for (Vec3& x : v) x = x.cwiseProduct(s);
    scaled = buildData(TriangleMesh(std::move(v), m_data->mesh.triangles(),
                                    m_data->mesh.name() + " (scaled)"),
                       m_data->tree.settings(), ShapeFrame::Mesh, m_data->meshFromShape);
  }
  m_scaled = std::move(scaled);
  m_scaling = scaling;
}

void MeshShape::calculateLocalInertia(btScalar mass, btVector3& inertia) const {
  // Bullet reads the result as the diagonal of the inertia tensor in the shape's frame: exact
  // when that frame is the principal frame (see principalTransform), the best diagonal
  // otherwise. Bullet gives no other place to say so, hence the warning.
  const MeshData& d = data();
  const MassProperties& m = d.mass;
  // 1e-6 relative: a recomputed principal frame (a scaled copy) is off by rounding only, and
  // an offset below this moves a body's dynamics by less than Bullet's own float rounding.
  constexpr double kPrincipalTolerance = 1e-6;
  Mat3 offDiagonal = m.inertia;
  offDiagonal.diagonal().setZero();
  const double offCentre = m.centerOfMass.norm() / d.mesh.bounds().extent().norm();
  const double offAxes = offDiagonal.cwiseAbs().maxCoeff() /
                         m.inertia.diagonal().cwiseAbs().maxCoeff();
  // Written so that 0/0 (a point mass, a mesh of one point) counts as principal.
  const bool principal = !(offCentre > kPrincipalTolerance) && !(offAxes > kPrincipalTolerance);
  if (!principal && d.inertiaWarning.raise()) {
    std::ostringstream message;
    message << "MeshShape '" << d.mesh.name() << "': calculateLocalInertia in a frame that is "
            << "not the principal frame (centre of mass " << offCentre << " of the mesh's "
            << "size off the origin, off-diagonal inertia " << offAxes << " of the largest "
            << "moment); the body will turn about the wrong point and axes. Build the "
            << "MeshData with adb::ShapeFrame::Principal, or put the shape in a "
            << "btCompoundShape at principalTransform().inverse()";
    warn(message.str());
  }
  inertia = toBt(m.inertia.diagonal()) * mass;
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
  // Casts (rayTest, convexSweepTest, CCD) walk the tree along the cast instead of taking
  // every triangle in the box around it (mesh_casts.cpp). dynamic_cast: Bullet's callbacks
  // are local classes of btCollisionWorld.cpp, known only by these bases.
  if (auto* ray = dynamic_cast<btTriangleRaycastCallback*>(callback)) {
    performRaycast(ray);
    return;
  }
  if (auto* sweep = dynamic_cast<btTriangleConvexcastCallback*>(callback)) {
    performConvexcast(sweep);
    return;
  }
  const AdbTree& t = tree();
  const auto& verts = t.localVertices();
  forEachTriangleNear(t, Aabb{fromBt(aabbMin), fromBt(aabbMax)}, [&](std::uint32_t i) {
    btVector3 corners[3];
    for (int k = 0; k < 3; ++k) corners[k] = toBt(verts[t.triangles()[i][k]] + t.origin());
    callback->processTriangle(corners, 0, static_cast<int>(t.meshTriangle(i)));
  });
}

}  // namespace adb
