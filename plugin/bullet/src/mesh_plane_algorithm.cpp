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
#include "contact_selection.h"
#include "near_face_corners.h"

namespace adb {

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

  // Bullet's normal on body 1 points towards body 0. Every vertex within reach is a
  // candidate; the selection keeps the deepest and the widest support (contact_selection.h).
  const btVector3 normalOnB = m_swapped ? -nWorld : nWorld;
  std::uint32_t stack[64];  // at most one pending sibling per level of a <= 29-level tree
  int top = 0;
  stack[top++] = 0;
  std::uint64_t visited = 0;  // nodes and triangles
  double closest = std::numeric_limits<double>::infinity();  // the nearest candidate's distance
  while (top > 0) {
    ++visited;
    const Node& node = tree.nodes()[stack[--top]];
    const Vec3 centre = 0.5 * (node.boxLo() + node.boxHi());
    const Vec3 half = 0.5 * (node.boxHi() - node.boxLo());
    if (n.dot(centre) - n.cwiseAbs().dot(half) + c > reach) continue;  // all above the plane
    if (!node.isLeaf()) {
      stack[top++] = node.firstChild();
      stack[top++] = node.firstChild() + 1;
      continue;
    }
    for (std::uint32_t t = node.firstTriangle(); t < node.firstTriangle() + node.triangleCount();
         ++t) {
      ++visited;
      for (std::uint32_t v : tree.triangles()[t]) {
        const Vec3& x = tree.localVertices()[v];
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
      }
    }
  }
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
