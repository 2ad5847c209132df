// ManifoldAlgorithm: the manifold shared by adb's Bullet algorithms.
#include "adb/bullet/manifold_algorithm.h"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>

#include "adb/bullet/dispatcher.h"
#include "conversions.h"

namespace adb {

btPersistentManifold* ManifoldAlgorithm::manifoldFor(const btCollisionObjectWrapper* body0,
                                                     const btCollisionObjectWrapper* body1,
                                                     btManifoldResult* result) {
  if (!m_manifold) {
    m_manifold = m_dispatcher->getNewManifold(body0->getCollisionObject(),
                                               body1->getCollisionObject());
  }
  result->setPersistentManifold(m_manifold);
  return m_manifold;
}

bool ManifoldAlgorithm::acceptPoses(const btCollisionObjectWrapper* body0,
                                    const btCollisionObjectWrapper* body1) {
  bool usable = true;
  for (const btCollisionObjectWrapper* body : {body0, body1}) {
    const PoseDefect defect = poseDefect(detail::toPose(body->getWorldTransform()));
    if (defect == PoseDefect::None) continue;
    usable = false;
    // Rare: the lookup is paid only when something is wrong.
    if (auto* dispatcher = dynamic_cast<Dispatcher*>(m_dispatcher)) {
      dispatcher->reportBadPose(body->getCollisionObject(), defect);
    }
  }
  if (!usable && m_manifold) m_manifold->clearManifold();
  return usable;
}

}  // namespace adb
