// MeshPlaneAlgorithm: mesh vertices against a static plane, pruned by the tree's boxes.
#include "mesh_plane_algorithm.h"

#include <BulletCollision/BroadphaseCollision/btDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btStaticPlaneShape.h>

#include <cstdint>

#include "adb/bullet/mesh_shape.h"
#include "contact_selection.h"

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
      }
    }
  }
  return visited;
}

}  // namespace adb
