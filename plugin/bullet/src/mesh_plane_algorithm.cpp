// MeshPlaneAlgorithm: mesh vertices against a static plane, pruned by the tree's boxes.
#include "mesh_plane_algorithm.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <BulletCollision/BroadphaseCollision/btDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>

#include <cstdint>

#include "adb/bullet/mesh_shape.h"
#include "adb/core/box_query.h"
#include "contact_selection.h"
#include "near_face_corners.h"

namespace adb {
namespace {

// The half-space n . x + c <= 0 (tree-local, n unit) as a box that holds every point of the
// tree's mesh below the plane: its top face on the plane, `half` past the mesh on every side.
OrientedBox halfSpaceBelow(const Vec3& n, double c, const AdbTree& tree, double reach) {
  const Node& root = tree.root();
  const double size = (root.boxHi() - root.boxLo()).norm() +
                      std::max(root.boxLo().norm(), root.boxHi().norm());
  const double half = 2.0 * (size + std::abs(c) + reach) + 1.0;
  // Two axes across n: any pair completing an orthonormal frame.
  const Vec3 helper = std::abs(n.x()) < 0.6 ? Vec3::UnitX() : Vec3::UnitY();
  const Vec3 u = n.cross(helper).normalized();
  OrientedBox box;
  box.axes.col(0) = n;
  box.axes.col(1) = u;
  box.axes.col(2) = n.cross(u);
  box.centre = -(c + half) * n;  // the plane's point nearest the origin, `half` below
  box.half = Vec3::Constant(half);
  return box;
}

}  // namespace

std::uint64_t MeshPlaneAlgorithm::collideNow(const btCollisionObjectWrapper* body0,
                                            const btCollisionObjectWrapper* body1,
                                            const btDispatcherInfo&, btManifoldResult* result) {
  manifoldFor(body0, body1, result);
  detail::ContactSelection selection;
  const std::uint64_t visited =
      gather(body0, body1, result->m_closestPointDistanceThreshold, selection);
  writeSelection(selection, *result);
  return visited;
}

bool MeshPlaneAlgorithm::gathersOffThread(const btCollisionObjectWrapper*,
                                          const btCollisionObjectWrapper*) const {
  return true;
}

std::uint64_t MeshPlaneAlgorithm::gather(const btCollisionObjectWrapper* body0,
                                        const btCollisionObjectWrapper* body1, btScalar,
                                        detail::ContactSelection& selection) const {
  selection.clear();
  const btCollisionObjectWrapper* meshWrap = m_swapped ? body1 : body0;
  const btCollisionObjectWrapper* planeWrap = m_swapped ? body0 : body1;
  const auto* mesh = static_cast<const MeshShape*>(meshWrap->getCollisionShape());
  const auto* plane = static_cast<const btStaticPlaneShape*>(planeWrap->getCollisionShape());
  const btTransform& meshPose = meshWrap->getWorldTransform();
  const btTransform& planePose = planeWrap->getWorldTransform();

  // The plane in the world, then in the tree's local frame: distance(x) = n . x + c.
  const btVector3 nWorld = planePose.getBasis() * plane->getPlaneNormal();
  const btScalar dWorld = nWorld.dot(planePose.getOrigin()) + plane->getPlaneConstant();
  const btVector3 nLocalBt = meshPose.getBasis().transpose() * nWorld;
  const AdbTree& tree = mesh->tree();
  const Vec3 n(nLocalBt.x(), nLocalBt.y(), nLocalBt.z());
  const double c = n.dot(tree.origin()) + nWorld.dot(meshPose.getOrigin()) - dWorld;
  const double reach = contactReach() + mesh->getMargin();

  // Bullet's normal on body 1 points towards body 0. The vertices within reach are the
  // candidates; the selection keeps the deepest and the widest support (contact_selection.h).
  // They are sampled as a box floor's are: each region of the tree gives its deepest
  // (forEachDeepestTriangleNear, the plane's half-space as a box larger than the mesh).
  // Visiting every vertex within reach cost a gear lying flat 1,200 units a step, and a
  // pile of 50 on a plane more than a quarter of exact contacts' whole need: under that
  // budget the plane pairs were skipped and the gears fell through (docs/bullet-results.md).
  const btVector3 normalOnB = m_swapped ? -nWorld : nWorld;
  const auto& vertices = tree.localVertices();
  std::uint64_t visited = 0;  // nodes and triangles
  double closest = std::numeric_limits<double>::infinity();  // the nearest candidate's distance
  const auto contactsOf = [&](std::uint32_t t) {
    ++visited;
    double deepest = -std::numeric_limits<double>::infinity();
    for (std::uint32_t v : tree.triangles()[t]) {
      const Vec3& x = vertices[v];
      const double distance = n.dot(x) + c;
      if (!(distance <= reach)) continue;
      const Vec3 m = x + tree.origin();
      const btVector3 onMesh = meshPose(btVector3(static_cast<btScalar>(m.x()),
                                                  static_cast<btScalar>(m.y()),
                                                  static_cast<btScalar>(m.z())));
      const btVector3 onPlane = onMesh - nWorld * static_cast<btScalar>(distance);
      selection.add({normalOnB, m_swapped ? onMesh : onPlane,
                     static_cast<btScalar>(distance - mesh->getMargin()),
                     static_cast<int>(tree.meshTriangle(t))});
      closest = std::min(closest, distance - mesh->getMargin());
      deepest = std::max(deepest, -distance);
    }
    return deepest;
  };
  visited += forEachDeepestTriangleNear(tree, halfSpaceBelow(n, c, tree, reach), reach,
                                        contactRegionLevel(), 0.0, contactsOf);
  if (speculativeReach() > 0 && std::isfinite(closest)) {
    // A fast body's candidates are its lowest vertices, hundreds at one distance for a face
    // falling flat: the selection kept the first it found, in one corner of the face, and
    // the solver stopped that corner only (a gear at 50 m/s went 0.14 into the plane, 0.33
    // at 100). The four lowest corners of its root box at the closest vertex's distance
    // (a hair less: the deepest, kept and written first) hold the whole face; no corner
    // claims more depth than the mesh has.
    const btScalar distance = std::nextafter(static_cast<btScalar>(closest),
                                             -std::numeric_limits<btScalar>::infinity());
    for (const btVector3& onMesh : detail::nearFaceCorners(*mesh, meshPose, -nWorld)) {
      const btVector3 onPlane = onMesh - nWorld * distance;
      selection.add({normalOnB, m_swapped ? onMesh : onPlane, distance, -1});
    }
  }
  return visited;
}

}  // namespace adb
