// ManifoldAlgorithm: the manifold, the pose check and the hand-over to the scheduler.
#include "manifold_algorithm.h"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btCollisionShape.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <cmath>
#include <limits>

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

btTransform ManifoldAlgorithm::meshInOther(const btTransform& transform0,
                                           const btTransform& transform1) const {
  return m_swapped ? transform0.inverseTimes(transform1) : transform1.inverseTimes(transform0);
}

void ManifoldAlgorithm::rememberPoses(const btCollisionObjectWrapper* body0,
                                      const btCollisionObjectWrapper* body1) {
  const btTransform pose = meshInOther(body0->getWorldTransform(), body1->getWorldTransform());
  const btQuaternion rotation = pose.getRotation();
  for (int i = 0; i < 3; ++i) m_lastOrigin[i] = pose.getOrigin()[i];
  for (int i = 0; i < 4; ++i) m_lastRotation[i] = static_cast<float>(rotation[i]);
  btVector3 centre;
  btScalar radius = 0;
  (m_swapped ? body1 : body0)->getCollisionShape()->getBoundingSphere(centre, radius);
  m_meshReach = static_cast<float>(centre.length() + radius);
}

btScalar ManifoldAlgorithm::motionSinceLastRun(const btTransform& transform0,
                                               const btTransform& transform1) const {
  if (m_lastRun == 0) return std::numeric_limits<btScalar>::infinity();
  // A mesh point p moved by at most |t' - t| + 2 sin(theta/2) |p|, theta the angle between
  // the two rotations. With d = |q' - q| (q' taken on q's side), 1 - cos(theta/2) = d^2/2:
  // from the difference, not from 1 - (q . q')^2, which loses all digits near rest.
  const btTransform now = meshInOther(transform0, transform1);
  const btQuaternion rotation = now.getRotation();
  btScalar dot = 0;
  for (int i = 0; i < 4; ++i) dot += rotation[i] * static_cast<btScalar>(m_lastRotation[i]);
  const btScalar side = dot < 0 ? btScalar(-1) : btScalar(1);
  btScalar d2 = 0;
  for (int i = 0; i < 4; ++i) {
    const btScalar d = rotation[i] - side * static_cast<btScalar>(m_lastRotation[i]);
    d2 += d * d;
  }
  const btScalar oneMinusCos = btMin(d2 / 2, btScalar(1));
  const btScalar sine = btSqrt(oneMinusCos * (2 - oneMinusCos));
  const btVector3 last(m_lastOrigin[0], m_lastOrigin[1], m_lastOrigin[2]);
  return (now.getOrigin() - last).length() + 2 * sine * static_cast<btScalar>(m_meshReach);
}

btScalar ManifoldAlgorithm::breakingThreshold() const {
  return m_manifold ? m_manifold->getContactBreakingThreshold() : btScalar(0);
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

namespace {

// Whether a rigid body's velocities are finite (any other object has none).
bool finiteVelocities(const btCollisionObject* object) {
  const btRigidBody* body = btRigidBody::upcast(object);
  if (!body) return true;
  const btVector3 v = body->getLinearVelocity(), w = body->getAngularVelocity();
  return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()) &&
         std::isfinite(w.x()) && std::isfinite(w.y()) && std::isfinite(w.z());
}

}  // namespace

bool ManifoldAlgorithm::acceptPoses(const btCollisionObjectWrapper* body0,
                                    const btCollisionObjectWrapper* body1) {
  bool usable = true;
  for (const btCollisionObjectWrapper* body : {body0, body1}) {
    PoseDefect defect = poseDefect(detail::toPose(body->getWorldTransform()));
    // A NaN velocity makes a NaN pose only when the step integrates it, after the solver
    // has carried it through this pair's contacts to the other body: refused the same way.
    if (defect == PoseDefect::None && !finiteVelocities(body->getCollisionObject())) {
      defect = PoseDefect::NonFinite;
    }
    if (defect == PoseDefect::None) continue;
    usable = false;
    if (m_scheduler) m_scheduler->noteBadPose(body->getCollisionObject(), defect);
  }
  if (!usable && m_manifold) m_manifold->clearManifold();
  return usable;
}

}  // namespace adb
