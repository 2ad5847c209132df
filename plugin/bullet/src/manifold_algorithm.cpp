// ManifoldAlgorithm: the manifold, the pose check and the hand-over to the scheduler.
#include "manifold_algorithm.h"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>

#include "adb/bullet/dispatcher.h"
#include "conversions.h"
#include "frame_scheduler.h"

namespace adb {

ManifoldAlgorithm::ManifoldAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
                                     const btCollisionObjectWrapper* body0,
                                     const btCollisionObjectWrapper* body1, bool swapped)
    : btActivatingCollisionAlgorithm(ci, body0, body1), m_swapped(swapped) {
  // Looked up once per pair, not per step.
  if (auto* dispatcher = dynamic_cast<Dispatcher*>(ci.m_dispatcher1)) {
    m_scheduler = &detail::schedulerOf(*dispatcher);
  }
}

ManifoldAlgorithm::~ManifoldAlgorithm() {
  if (m_manifold) m_dispatcher->releaseManifold(m_manifold);
}

void ManifoldAlgorithm::processCollision(const btCollisionObjectWrapper* body0,
                                         const btCollisionObjectWrapper* body1,
                                         const btDispatcherInfo& info,
                                         btManifoldResult* result) {
  if (!acceptPoses(body0, body1)) return;
  if (m_scheduler && m_scheduler->collecting()) {
    // The manifold is made now, in Bullet's dispatch order, not when the scheduler first
    // writes contacts: the solver visits manifolds in the order they were made, and a budget
    // that reorders the writing (a pair cut, then completed by a refinement) must not
    // reorder the solver, or a budget that is never reached would change the simulation.
    ensureManifold(body0, body1);
    m_scheduler->defer(this, body0, body1);
    return;
  }
  m_lastWork = collideNow(body0, body1, info, result);
}

void ManifoldAlgorithm::keepLastContacts(const btCollisionObjectWrapper* body0,
                                         const btCollisionObjectWrapper* body1) {
  if (!m_manifold) return;
  btManifoldResult result(body0, body1);
  result.setPersistentManifold(m_manifold);
  result.refreshContactPoints();
}

void ManifoldAlgorithm::ensureManifold(const btCollisionObjectWrapper* body0,
                                       const btCollisionObjectWrapper* body1) {
  if (!m_manifold) {
    m_manifold = m_dispatcher->getNewManifold(body0->getCollisionObject(),
                                               body1->getCollisionObject());
  }
}

btPersistentManifold* ManifoldAlgorithm::manifoldFor(const btCollisionObjectWrapper* body0,
                                                     const btCollisionObjectWrapper* body1,
                                                     btManifoldResult* result) {
  ensureManifold(body0, body1);
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
    if (m_scheduler) m_scheduler->noteBadPose(body->getCollisionObject(), defect);
  }
  if (!usable && m_manifold) m_manifold->clearManifold();
  return usable;
}

}  // namespace adb
