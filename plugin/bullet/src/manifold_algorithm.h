// Internal: ManifoldAlgorithm, what adb's Bullet collision algorithms share, and
// CreateAlgorithm, the factory Bullet's dispatcher calls.
//
// Shared: which body is the mesh, a persistent manifold made on first use and released
// with the algorithm (and a second: speculative contacts, or a mesh-mesh pair's second group
// of contacts), the reach of its contacts (speculative for fast bodies that ask for
// continuous collision detection), the pose check, and the hand-over to the step's
// scheduler. Under adb::Dispatcher every pair (a compound's children included) is only
// noted while Bullet dispatches; the scheduler then runs them all within the step's one
// budget (frame_scheduler.h). Elsewhere (a plain btCollisionDispatcher, contactTest) a
// pair is collided at once.
#pragma once

#include <BulletCollision/BroadphaseCollision/btDispatcher.h>
#include <BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btCollisionCreateFunc.h>
#include <LinearMath/btTransform.h>

#include <cstdint>
#include <new>

#include "adb/bullet/precision.h"
#include "contact_selection.h"

class btManifoldResult;

namespace adb {

namespace detail {
class ContactSelection;
class FrameScheduler;
struct ContactGroups;
}

class ManifoldAlgorithm : public btActivatingCollisionAlgorithm {
 public:
  /// `swapped`: body0 is the other shape and body1 the mesh.
  ManifoldAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
                    const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                    bool swapped);
  ~ManifoldAlgorithm() override;

  /// Bullet's entry: checks both poses, then hands the pair to the step's scheduler during
  /// adb::Dispatcher's dispatch, or collides it at once.
  void processCollision(const btCollisionObjectWrapper* body0,
                        const btCollisionObjectWrapper* body1, const btDispatcherInfo& info,
                        btManifoldResult* result) final;

  /// Collides the pair now and writes its contacts into `result` (its manifold set first).
  /// Returns the work done, in node-pair units (tree nodes and triangles visited).
  virtual std::uint64_t collideNow(const btCollisionObjectWrapper* body0,
                                   const btCollisionObjectWrapper* body1,
                                   const btDispatcherInfo& info, btManifoldResult* result) = 0;
  /// Whether the scheduler refines this pair under the budget (a mesh-mesh pair's
  /// traversal); the others are collided whole or not at all in a step.
  virtual bool refinable() const { return false; }
  /// collideNow, for the scheduler: remembers the work as the next step's estimate.
  /// `step` is the scheduler's step count: the pair ran then.
  std::uint64_t collideScheduled(const btCollisionObjectWrapper* body0,
                                 const btCollisionObjectWrapper* body1,
                                 const btDispatcherInfo& info, btManifoldResult* result,
                                 std::uint64_t step) {
    m_lastWork = collideWithReach(body0, body1, info, result);
    m_lastRun = step;
    rememberPoses(body0, body1);
    return m_lastWork;
  }
  /// Steps without a budget gather the contacts of closed-form pairs on the scheduler's
  /// pool (a mesh against a plane, a box, a sphere or a capsule): whether this pair is one,
  /// reading only its shapes, its poses and its own state. Such a pair's collideNow is
  /// manifoldFor, gather and writeSelection, so both routes write the same points.
  virtual bool gathersOffThread(const btCollisionObjectWrapper* body0,
                                const btCollisionObjectWrapper* body1) const;
  /// The stepping thread, before gather(): makes the pair's manifold (its breaking threshold
  /// is how far contacts reach).
  void prepareGather(const btCollisionObjectWrapper* body0,
                     const btCollisionObjectWrapper* body1) {
    ensureManifold(body0, body1);
  }
  /// Any thread, where gathersOffThread(): the pair's candidate contacts into `selection`
  /// (emptied first), touching nothing of Bullet's; returns the work. `closestPoints` is
  /// btManifoldResult::m_closestPointDistanceThreshold of the result it will be written
  /// through.
  virtual std::uint64_t gather(const btCollisionObjectWrapper* body0,
                               const btCollisionObjectWrapper* body1, btScalar closestPoints,
                               detail::ContactSelection& selection) const;
  /// collideScheduled for a gathered pair, on the stepping thread: writes `selection` as
  /// collideNow would have (through the speculative manifold where the pair has one) and
  /// remembers `work`, the step and the poses.
  void writeGathered(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                     btManifoldResult* result, detail::ContactSelection& selection,
                     std::uint64_t work, std::uint64_t step);
  /// An upper bound on how far any point of the mesh has moved against the other body
  /// since the last collideScheduled (infinite if it never ran), for the wrappers' world
  /// transforms: a skipped pair's kept contacts stay true while it is small.
  btScalar motionSinceLastRun(const btTransform& transform0, const btTransform& transform1) const;
  /// Whether `motion` (motionSinceLastRun() for the step's poses) is small enough for the
  /// pair's last contacts, re-measured at the new poses, to be still where the surfaces
  /// meet: less than kRestingMotion of the breaking threshold.
  bool barelyMoved(btScalar motion) const;
  /// Whether the pair may keep its contacts this step instead of colliding again: they were
  /// made when the pair last ran, its manifold still holds some, it barelyMoved(motion),
  /// and neither body is fast enough for speculative contacts.
  bool contactsStillHold(btScalar motion) const;
  /// Whether the pair's manifold holds any contact (a skipped pair keeps those).
  bool holdsContacts() const;
  /// The sum of the contact normals the pair's manifold holds (Bullet's normal on body 1,
  /// pointing towards body 0); zero before its first contacts. Read on any thread before
  /// the pair writes its contacts: only the pair writes its manifold.
  btVector3 lastNormalsOnB() const;
  /// The deepest penetration of the contacts the manifold holds, re-measured at the bodies'
  /// current poses (0 when none penetrates, or it holds none): how far a pair that keeps its
  /// contacts has sunk into the other body since they were made.
  btScalar keptDepth() const;
  /// Notes that the pair's contacts were made now, for bodies posed as `body0` and `body1`:
  /// what motionSinceLastRun() measures from. The scheduler's, for mesh-mesh pairs.
  void noteContactsMade(const btCollisionObjectWrapper* body0,
                        const btCollisionObjectWrapper* body1, std::uint64_t step) {
    m_lastRun = step;
    rememberPoses(body0, body1);
  }
  /// The scheduler's measure of the last collideScheduled's time (microseconds).
  double lastMicros() const { return m_lastMicros; }
  void setLastMicros(double micros) { m_lastMicros = micros; }
  /// Work units of the last collideNow: the next step's estimate of this pair's cost.
  std::uint64_t lastWork() const { return m_lastWork; }
  /// The scheduler's step at which collideScheduled last ran (0: never).
  std::uint64_t lastRun() const { return m_lastRun; }
  /// The contact breaking threshold Bullet gave the pair's manifold (0 before it has one).
  btScalar breakingThreshold() const { return m_threshold; }
  /// How much farther than the breaking threshold contacts reach this step: where either
  /// body asks for continuous collision detection (setCcdMotionThreshold) and moves more than
  /// its threshold in this step, how far the bodies can close in the step; 0 otherwise.
  /// Contacts that far apart are speculative: Bullet's solver removes only the approach that
  /// would carry the bodies past them. They go to the pair's second manifold
  /// (speculative_result.h), rebuilt every step.
  btScalar speculativeReach() const { return m_speculative; }
  /// Whether the pair had speculative contacts within the last kLandingSteps steps: a fast
  /// body that has just reached the other one is still settling onto it.
  bool landing() const { return m_landingSteps > 0; }
  static constexpr std::uint8_t kLandingSteps = 30;
  /// How far apart features make contacts this step: breakingThreshold() plus
  /// speculativeReach().
  btScalar contactReach() const { return m_threshold + m_speculative; }
  /// How finely a pair of a mesh with a box or a plane samples its contacts: the tree's
  /// regions are 2^level (detail::kContactRegionLevel; the scheduler coarsens it under a
  /// binding budget, detail::kCoarseRegionLevel).
  int contactRegionLevel() const { return m_regionLevel; }
  void setContactRegionLevel(int level) { m_regionLevel = static_cast<std::uint8_t>(level); }
  /// Refreshes the pair's manifolds for the bodies' new poses (Bullet's refreshContactPoints)
  /// without colliding: what a pair the budget skipped keeps from its last step.
  void keepLastContacts(const btCollisionObjectWrapper* body0,
                        const btCollisionObjectWrapper* body1);

  btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                 btManifoldResult*) override {
    return 1;  // Bullet sweeps only convex bodies; meshes get speculative contacts instead
  }
  void getAllContactManifolds(btManifoldArray& manifolds) override {
    if (m_manifold) manifolds.push_back(m_manifold);
    if (m_secondManifold) manifolds.push_back(m_secondManifold);
  }

 protected:
  /// The pair's manifold (made on first use), set as `result`'s.
  btPersistentManifold* manifoldFor(const btCollisionObjectWrapper* body0,
                                    const btCollisionObjectWrapper* body1,
                                    btManifoldResult* result);
  detail::FrameScheduler* scheduler() const { return m_scheduler; }
  /// Writes `selection` into the pair's manifold through `result` and refreshes the
  /// manifold's points for the bodies' poses: how a gathered pair's collideNow ends.
  void writeSelection(detail::ContactSelection& selection, btManifoldResult& result);
  /// The manifold of this step's speculative contacts, or null when there are none to make.
  btPersistentManifold* speculativeManifold() const {
    return m_speculative > 0 ? m_secondManifold : nullptr;
  }
  /// A refinable (mesh-mesh) pair's second group of contacts, kept from step to step like
  /// the first, in the manifold a fast pair's speculative contacts use: null while the pair
  /// has speculative contacts, and before its first query.
  btPersistentManifold* secondGroupManifold() const {
    return m_speculative == 0 ? m_secondManifold : nullptr;
  }
  /// The manifolds the pair's contacts go to (pair_contacts.h): its manifold and its
  /// secondGroupManifold(); none before the pair's first dispatch.
  detail::ContactGroups contactGroups() const;

 private:
  /// Makes the pair's manifold if it has none (Bullet's dispatcher owns it; released with
  /// the algorithm).
  void ensureManifold(const btCollisionObjectWrapper* body0,
                      const btCollisionObjectWrapper* body1);
  /// Whether both bodies' poses are usable (adb/core/query.h, poseDefect) and their
  /// velocities finite. When one is not, the pair's manifold is emptied (its points would
  /// carry the NaN into the solver) and the body is reported to the scheduler: the pair is
  /// skipped.
  bool acceptPoses(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1);
  /// Keeps the mesh's pose in the other body's frame, and how far its points reach from
  /// its origin, for motionSinceLastRun.
  void rememberPoses(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1);
  /// collideNow through a result that sends speculative contacts to their manifold.
  std::uint64_t collideWithReach(const btCollisionObjectWrapper* body0,
                                 const btCollisionObjectWrapper* body1,
                                 const btDispatcherInfo& info, btManifoldResult* result);
  /// Sets speculativeReach() for this step, and readies the second manifold (made on first
  /// use): emptied for speculative contacts, or for a refinable pair without them a second
  /// group of contacts, emptied only of a fast step's speculative points.
  void setReach(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                btScalar timeStep);
  btTransform meshInOther(const btTransform& transform0, const btTransform& transform1) const;

  btPersistentManifold* m_manifold = nullptr;
  btPersistentManifold* m_secondManifold = nullptr;  // speculativeManifold, secondGroupManifold
  detail::FrameScheduler* m_scheduler = nullptr;  // set under adb::Dispatcher
  std::uint64_t m_lastWork = 0;
  std::uint64_t m_lastRun = 0;
  double m_lastMicros = 0.0;
  // The mesh's pose in the other body's frame when the pair last ran: the rotation as a
  // float quaternion (its error, 1e-7 of the mesh's reach, is far below any contact
  // threshold), so that the algorithm fits Bullet's default pool (algorithmPoolElementSize).
  btScalar m_lastOrigin[3] = {0, 0, 0};
  float m_lastRotation[4] = {0, 0, 0, 1};
  float m_meshReach = 0;  // the farthest point of the mesh from its origin, bounded

 protected:
  // Declared here rather than with the protected functions above: it fills the padding after
  // m_meshReach, which keeps every algorithm within Bullet's default pool element (192 bytes
  // in double precision; Dynamics.DefaultAlgorithmPoolHoldsTheAlgorithm).
  bool m_swapped;

 private:
  // Steps left in which the pair counts as landing (landing()); in the padding after
  // m_swapped.
  std::uint8_t m_landingSteps = 0;
  // contactRegionLevel(), in the same padding.
  std::uint8_t m_regionLevel = detail::kContactRegionLevel;
  btScalar m_threshold = 0;    // the manifold's breaking threshold as Bullet made it
  btScalar m_speculative = 0;  // speculativeReach() of this step
};

/// The dispatcher's factory for an algorithm constructed as Algo(ci, body0, body1, swapped);
/// set m_swapped for the mesh-second order. Algorithms live in the dispatcher's pool.
template <class Algo>
struct CreateAlgorithm : public btCollisionAlgorithmCreateFunc {
  btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                 const btCollisionObjectWrapper* body0,
                                                 const btCollisionObjectWrapper* body1) override {
    void* memory = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(Algo));
    return new (memory) Algo(ci, body0, body1, m_swapped);
  }
};

}  // namespace adb
