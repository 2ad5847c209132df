// ManifoldAlgorithm: the manifold shared by adb's Bullet algorithms.
#include "adb/bullet/manifold_algorithm.h"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>

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

}  // namespace adb
