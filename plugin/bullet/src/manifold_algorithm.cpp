// ManifoldAlgorithm: the manifold, the pose check and the hand-over to the scheduler.
#include "manifold_algorithm.h"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btCollisionShape.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <cmath>
#include <limits>

#include "adb/bullet/dispatcher.h"
#include "contact_selection.h"
#include "conversions.h"
#include "frame_scheduler.h"
#include "pair_contacts.h"
#include "speculative_result.h"

namespace adb {

ManifoldAlgorithm::ManifoldAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
                                     const btCollisionObjectWrapper* body0,
                                     const btCollisionObjectWrapper* body1, bool swapped)
    : btActivatingCollisionAlgorithm(ci, body0, body1), m_swapped(swapped) {
  // Looked up once per pair, not per step.
  if (auto* dispatcher = dynamic_cast<Dispatcher*>(ci.m_dispatcher1)) {
    m_scheduler = dispatcher->m_scheduler.get();
  }
}

ManifoldAlgorithm::~ManifoldAlgorithm() {
  if (m_manifold) m_dispatcher->releaseManifold(m_manifold);
  if (m_secondManifold) m_dispatcher->releaseManifold(m_secondManifold);
}

void ManifoldAlgorithm::processCollision(const btCollisionObjectWrapper* body0,
                                         const btCollisionObjectWrapper* body1,
                                         const btDispatcherInfo& info,
                                         btManifoldResult* result) {
  if (!acceptPoses(body0, body1)) return;
  // The manifold is made now, in Bullet's dispatch order, not when the scheduler first
  // writes contacts: the solver visits manifolds in the order they were made, and a budget
  // that reorders the writing (a pair cut, then completed by a refinement) must not
  // reorder the solver, or a budget that is never reached would change the simulation.
  ensureManifold(body0, body1);
  setReach(body0, body1, info.m_timeStep);
  if (m_scheduler && m_scheduler->collecting()) {
    m_scheduler->defer(this, body0, body1);
    return;
  }
  // Answered at once (a plain btCollisionDispatcher): a pair at rest keeps its contacts too.
  if (contactsStillHold(
          motionSinceLastRun(body0->getWorldTransform(), body1->getWorldTransform()))) {
    keepLastContacts(body0, body1);
    return;
  }
  m_lastWork = collideWithReach(body0, body1, info, result);
  noteContactsMade(body0, body1, m_lastRun + 1);
}

std::uint64_t ManifoldAlgorithm::collideWithReach(const btCollisionObjectWrapper* body0,
                                                  const btCollisionObjectWrapper* body1,
                                                  const btDispatcherInfo& info,
                                                  btManifoldResult* result) {
  btPersistentManifold* speculative = speculativeManifold();
  if (!speculative) return collideNow(body0, body1, info, result);
  result->setPersistentManifold(m_manifold);  // as collideNow would leave it
  detail::SpeculativeResult reach(*result, speculative, contactReach());
  return collideNow(body0, body1, info, &reach);
}

bool ManifoldAlgorithm::gathersOffThread(const btCollisionObjectWrapper*,
                                         const btCollisionObjectWrapper*) const {
  return false;
}

std::uint64_t ManifoldAlgorithm::gather(const btCollisionObjectWrapper*,
                                        const btCollisionObjectWrapper*, btScalar,
                                        detail::ContactSelection& selection) const {
  selection.clear();
  return 0;
}

void ManifoldAlgorithm::writeSelection(detail::ContactSelection& selection,
                                       btManifoldResult& result) {
  selection.write(result, !m_swapped, *m_manifold);
  result.refreshContactPoints();
}

void ManifoldAlgorithm::writeGathered(const btCollisionObjectWrapper* body0,
                                      const btCollisionObjectWrapper* body1,
                                      btManifoldResult* result,
                                      detail::ContactSelection& selection, std::uint64_t work,
                                      std::uint64_t step) {
  // As collideWithReach and collideNow: the result's manifold set, speculative points apart.
  result->setPersistentManifold(m_manifold);
  if (btPersistentManifold* speculative = speculativeManifold()) {
    detail::SpeculativeResult reach(*result, speculative, contactReach());
    writeSelection(selection, reach);
  } else {
    writeSelection(selection, *result);
  }
  m_lastWork = work;
  m_lastRun = step;
  rememberPoses(body0, body1);
}

void ManifoldAlgorithm::keepLastContacts(const btCollisionObjectWrapper* body0,
                                         const btCollisionObjectWrapper* body1) {
  if (!m_manifold) return;
  btManifoldResult result(body0, body1);
  detail::refreshContactGroups(result, contactGroups(), detail::KeptPoints::Slide);
}

detail::ContactGroups ManifoldAlgorithm::contactGroups() const {
  detail::ContactGroups groups;
  if (!m_manifold) return groups;
  groups.manifolds[groups.count++] = m_manifold;
  if (btPersistentManifold* second = secondGroupManifold()) {
    groups.manifolds[groups.count++] = second;
  }
  return groups;
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

namespace {

// How far, as a share of the breaking threshold, a mesh may move against the other body
// while its last contacts still stand: a pair at rest keeps them without colliding, and
// under a binding budget a pair with the world is left for last. Jolt skips its narrow
// phase below 1 mm and 2 degrees, PhysX below a fraction of the contact margin; a quarter
// of Bullet's threshold is 2 mm for a body 0.8 across (threshold 0.008), or a quarter of a
// degree of turn. On the 50-gear pile on a plane with exact contacts (docs/bullet-results.md,
// "Piles that fall asleep"), against never keeping contacts (`adb-demo --no-keep-contacts`):
// all asleep from step 929 against never, 4.4 against 11.5 ms a step. Other shares were
// tried with a temporary build switch on the same pile: 0.1 slept at step 1,104, 0.5 and 1.0
// (stale contacts, twice the timer resets) not at all by step 1,200.
constexpr btScalar kRestingMotion = btScalar(0.25);

}  // namespace

bool ManifoldAlgorithm::barelyMoved(btScalar motion) const {
  return motion < kRestingMotion * m_threshold;
}

bool ManifoldAlgorithm::holdsContacts() const {
  return m_manifold && m_manifold->getNumContacts() > 0;
}

bool ManifoldAlgorithm::contactsStillHold(btScalar motion) const {
  return m_lastRun != 0 && holdsContacts() &&
         m_speculative == 0 && barelyMoved(motion);
}

btVector3 ManifoldAlgorithm::lastNormalsOnB() const {
  btVector3 sum(0, 0, 0);
  const detail::ContactGroups groups = contactGroups();
  for (int g = 0; g < groups.count; ++g) {
    const btPersistentManifold& manifold = *groups.manifolds[g];
    for (int i = 0; i < manifold.getNumContacts(); ++i) {
      sum += manifold.getContactPoint(i).m_normalWorldOnB;
    }
  }
  return sum;
}

btScalar ManifoldAlgorithm::keptDepth() const {
  btScalar deepest = 0;
  const detail::ContactGroups groups = contactGroups();
  for (int g = 0; g < groups.count; ++g) {
    const btPersistentManifold& manifold = *groups.manifolds[g];
    for (int i = 0; i < manifold.getNumContacts(); ++i) {
      deepest = btMax(deepest, -detail::separationNow(manifold, manifold.getContactPoint(i)));
    }
  }
  return deepest;
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

namespace {

// How fast any point of a body can move: |v| + |w| r, r the farthest point of its shape
// from its origin. 0 for anything but a rigid body.
btScalar pointSpeedBound(const btCollisionObjectWrapper* body) {
  const btRigidBody* rigid = btRigidBody::upcast(body->getCollisionObject());
  if (!rigid) return 0;
  btVector3 centre;
  btScalar radius = 0;
  body->getCollisionShape()->getBoundingSphere(centre, radius);
  return rigid->getLinearVelocity().length() +
         rigid->getAngularVelocity().length() * (centre.length() + radius);
}

// Whether a body asks for continuous collision detection and moves farther than its
// threshold in this step: Bullet's own test for its convex sweeps
// (btDiscreteDynamicsWorld::integrateTransforms).
bool wantsSweep(const btCollisionObjectWrapper* body, btScalar timeStep) {
  const btRigidBody* rigid = btRigidBody::upcast(body->getCollisionObject());
  if (!rigid || rigid->getCcdSquareMotionThreshold() <= 0) return false;
  const btScalar motion = rigid->getLinearVelocity().length() * timeStep;
  return motion * motion > rigid->getCcdSquareMotionThreshold();
}

// A body moving more than this share of its thinnest extent in a step may cross a surface
// without any of its triangles crossing it at the step's end: Bullet's advice for a CCD
// motion threshold is about half the body's smallest dimension.
constexpr btScalar kThinCrossingShare = btScalar(0.5);

// Whether a dynamic body moves against the world (a static or kinematic `other`) by more
// than kThinCrossingShare of its thinnest local extent in this step. Such a body gets the
// sweep it did not ask for: a thin gear falling at 7.4 m/s (its thickness per step) into a
// closed mesh bin crossed the floor's top face in a step the budget cut, ended wholly inside
// the floor where no triangles cross, and fell out of the world (the mesh bin at 1/16 of
// the need lost 7 gears; exact contacts were lucky to catch each first crossing).
bool outrunsItsThickness(const btCollisionObjectWrapper* body,
                         const btCollisionObjectWrapper* other, btScalar timeStep) {
  if (!other->getCollisionObject()->isStaticOrKinematicObject()) return false;
  const btRigidBody* rigid = btRigidBody::upcast(body->getCollisionObject());
  if (!rigid || rigid->isStaticOrKinematicObject()) return false;
  btVector3 lo, hi;
  body->getCollisionShape()->getAabb(btTransform::getIdentity(), lo, hi);
  const btVector3 size = hi - lo;
  const btScalar thinnest = size[size.minAxis()];
  const btScalar motion = rigid->getLinearVelocity().length() * timeStep;
  return motion > kThinCrossingShare * thinnest;
}

}  // namespace

// Bodies that do not ask for a sweep get no speculative contacts, so nothing changes for
// them, except a thin mesh body outrunning its thickness against a mesh world
// (outrunsItsThickness).
void ManifoldAlgorithm::setReach(const btCollisionObjectWrapper* body0,
                                 const btCollisionObjectWrapper* body1, btScalar timeStep) {
  const bool wasSpeculative = m_speculative > 0;
  m_speculative = 0;
  const bool asked = wantsSweep(body0, timeStep) || wantsSweep(body1, timeStep);
  // Read only where it changes something: a body that asked is swept anyway.
  const bool thinAndFast = !asked && refinable() &&
                           (outrunsItsThickness(body0, body1, timeStep) ||
                            outrunsItsThickness(body1, body0, timeStep));
  if (timeStep > 0 && (asked || thinAndFast)) {
    // Any two points of the bodies close by at most the sum of their speed bounds in a
    // step. acceptPoses refused non-finite velocities; a huge one still gives a finite reach.
    const btScalar closing = (pointSpeedBound(body0) + pointSpeedBound(body1)) * timeStep;
    if (std::isfinite(closing)) m_speculative = closing;
  }
  // Landing is for the bodies that asked for sweeps: a thin body swept unasked stops on the
  // surface and is scheduled as any other (run whole for its landing, the mesh bin's gears
  // overran a 3,583 node-pair budget 2x at p99; without, 1.2x).
  if (m_speculative > 0 && asked) {
    m_landingSteps = kLandingSteps;
  } else if (m_landingSteps > 0) {
    --m_landingSteps;
  }
  if ((m_speculative > 0 || refinable()) && !m_secondManifold) {
    m_secondManifold = m_dispatcher->getNewManifold(body0->getCollisionObject(),
                                                    body1->getCollisionObject());
  }
  if (!m_secondManifold) return;
  if (m_speculative > 0) {
    // Last step's speculative points said where the bodies might meet then: start afresh.
    m_secondManifold->clearManifold();
    m_secondManifold->setContactBreakingThreshold(contactReach());
    return;
  }
  // A second group of contacts, with the first's threshold (Bullet's, as a new manifold
  // has it before the first has been made).
  if (wasSpeculative) m_secondManifold->clearManifold();
  if (m_threshold > 0) m_secondManifold->setContactBreakingThreshold(m_threshold);
}

void ManifoldAlgorithm::ensureManifold(const btCollisionObjectWrapper* body0,
                                       const btCollisionObjectWrapper* body1) {
  if (!m_manifold) {
    m_manifold = m_dispatcher->getNewManifold(body0->getCollisionObject(),
                                               body1->getCollisionObject());
    m_threshold = m_manifold->getContactBreakingThreshold();
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
    PoseDefect defect = poseDefect(toPose(body->getWorldTransform()));
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
  if (!usable && m_secondManifold) m_secondManifold->clearManifold();
  return usable;
}

}  // namespace adb
