// SpeculativeResult: btManifoldResult::addContactPoint for points beyond the breaking
// threshold, written into the speculative manifold without matching.
#include "speculative_result.h"

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>

namespace adb::detail {

void SpeculativeResult::addContactPoint(const btVector3& normalOnBInWorld,
                                        const btVector3& pointInWorld, btScalar depth) {
  if (!m_speculative || depth <= m_manifoldPtr->getContactBreakingThreshold()) {
    btManifoldResult::addContactPoint(normalOnBInWorld, pointInWorld, depth);
    return;
  }
  if (!(depth <= m_reach)) return;
  // As btManifoldResult::addContactPoint (Bullet 3.24) writes a point, less the matching with
  // kept points: the manifold was cleared this step, and a full one keeps the deepest and
  // widest four (btPersistentManifold::sortCachedPoints).
  const btCollisionObject* object0 = m_body0Wrap->getCollisionObject();
  const btCollisionObject* object1 = m_body1Wrap->getCollisionObject();
  const bool swapped = m_speculative->getBody0() != object0;
  const btVector3 pointA = pointInWorld + normalOnBInWorld * depth;
  const btCollisionObject* onA = swapped ? object1 : object0;
  const btCollisionObject* onB = swapped ? object0 : object1;
  btManifoldPoint point(onA->getWorldTransform().invXform(pointA),
                        onB->getWorldTransform().invXform(pointInWorld), normalOnBInWorld, depth);
  point.m_positionWorldOnA = pointA;
  point.m_positionWorldOnB = pointInWorld;
  point.m_combinedFriction = calculateCombinedFriction(object0, object1);
  point.m_combinedRestitution = calculateCombinedRestitution(object0, object1);
  point.m_combinedRollingFriction = calculateCombinedRollingFriction(object0, object1);
  point.m_combinedSpinningFriction = calculateCombinedSpinningFriction(object0, object1);
  point.m_partId0 = swapped ? m_partId1 : m_partId0;
  point.m_partId1 = swapped ? m_partId0 : m_partId1;
  point.m_index0 = swapped ? m_index1 : m_index0;
  point.m_index1 = swapped ? m_index0 : m_index1;
  m_speculative->addManifoldPoint(point, true);
}

}  // namespace adb::detail
