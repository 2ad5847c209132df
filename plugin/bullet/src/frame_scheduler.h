// Internal: FrameScheduler, which collects the adb pairs of a step while Bullet dispatches
// and then spends the step's budget across them (policy: adb/bullet/frame_budget.h).
#pragma once

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <LinearMath/btTransform.h>

#include <BulletCollision/BroadphaseCollision/btDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <vector>

#include "adb/bullet/frame_budget.h"
#include "adb/core/query.h"

namespace adb {
class ManifoldAlgorithm;
class MeshMeshAlgorithm;
}

namespace adb::detail {

/// A pair noted during the dispatch: enough to rebuild Bullet's wrappers and result
/// afterwards (the dispatch's own live on its stack; a compound's child wrappers only
/// during its call), and the pair's scheduling state.
struct DeferredPair {
  ManifoldAlgorithm* algorithm;
  const btCollisionObject* object0;
  const btCollisionObject* object1;
  const btCollisionShape* shape0;  // the wrapper's shape: a compound's child for a child pair
  const btCollisionShape* shape1;
  btTransform transform0, transform1;  // the wrappers' world transforms, kept by value
  int partId0, index0, partId1, index1;
  std::uint32_t sequence;  // order of the dispatch: ties in the whole pairs' order
  // A whole pair: how far its mesh moved against the other body since it last ran (its
  // kept contacts' error), infinite if it never ran. The most moved run first.
  btScalar motion = 0;
  // Scheduling state of this step.
  std::uint64_t grant = 0;     // node pairs granted this step (all its queries)
  double confidence = 0.0;     // see FrameStats::meanConfidence
  double completeness = 0.0;   // see FrameStats::meanCompleteness: the refinement's order
  StopReason stop = StopReason::Completed;
  bool written = false;        // its contacts are in its manifold

  /// Completed, stopped on quality or with its contacts found: nothing left to refine.
  bool decided() const { return !isBudgetStop(stop); }
  /// The mesh-mesh algorithm of a refinable pair.
  MeshMeshAlgorithm& meshMesh() const;
};

/// Bullet's wrappers of a deferred pair, rebuilt as the dispatch made them.
struct PairWrappers {
  btCollisionObjectWrapper body0, body1;
  explicit PairWrappers(const DeferredPair& pair);
};

class FrameScheduler {
 public:
  /// Starts a step: pairs noted from now on are scheduled by run().
  void begin();
  bool collecting() const { return m_collecting; }
  /// Notes a pair during the dispatch.
  void defer(ManifoldAlgorithm* algorithm, const btCollisionObjectWrapper* body0,
             const btCollisionObjectWrapper* body1);
  /// Spends the budget across the noted pairs, writes their manifolds, ends the step.
  void run(const FrameSettings& settings, const btDispatcherInfo& info);
  const FrameStats& stats() const { return m_stats; }
  /// The last step's mesh-mesh pairs (Dispatcher::lastMeshPairs).
  void meshPairs(std::vector<MeshPairReport>& out) const;
  /// Notes a body with an unusable pose for this step and, the first time this step, tells
  /// the callback.
  void noteBadPose(const btCollisionObject* body, PoseDefect defect);
  void setBadPoseCallback(std::function<void(const BadPose&)> callback) {
    m_badPoseCallback = std::move(callback);
  }
  /// Ends the collection without a run (the dispatch threw): later queries are answered at
  /// once again.
  void abandon() { m_collecting = false; }

 private:
  using Clock = std::chrono::steady_clock;

  void firstPass(const FrameSettings& settings);
  bool binding(const FrameSettings& settings) const;
  double expectedWholeMicros(const ManifoldAlgorithm& algorithm) const;
  void refine(const FrameSettings& settings);
  /// Collides a pair that is not refined (mesh against a convex shape, a plane or another
  /// concave shape) when its last cost fits in `share` node pairs and `microsShare`, or when
  /// it costs more than the whole budget and has waited kMaxSkippedSteps; false (not run)
  /// otherwise.
  bool runWhole(DeferredPair& pair, std::uint64_t share, double microsShare,
                const FrameSettings& settings);
  void runWholesLeft(const FrameSettings& settings);
  /// Pairs the budget left unrun keep their last contacts, refreshed for the new poses.
  void keepSkipped();
  /// Runs one query of `pair`; returns the work it did (node pairs and triangle tests).
  /// `starved`: granted less than it wants (a new query then descends deepest first).
  std::uint64_t query(DeferredPair& pair, std::uint64_t grant, double micros,
                      const FrameSettings& settings, bool resume, bool starved = false);
  double writePair(DeferredPair& pair, const FrameSettings& settings);
  bool outOfTime(const FrameSettings& settings) const;
  void writeContacts(const FrameSettings& settings);
  std::uint64_t nodePairsLeft(const FrameSettings& settings) const;
  /// Microseconds left of a time budget, less the margin and, with `holdBackWrites`, the
  /// expected cost of the mesh-mesh contacts still to write.
  double microsLeft(const FrameSettings& settings, bool holdBackWrites = true) const;
  void updateMargin(const FrameSettings& settings);
  std::uint64_t share(const FrameSettings& settings, std::uint64_t waiting) const;

  std::vector<DeferredPair> m_pairs;   // mesh-mesh, refined (reused: no allocation)
  std::vector<DeferredPair> m_wholes;  // the others: run whole or not at all
  const btDispatcherInfo* m_info = nullptr;  // the dispatch's, during run()
  std::vector<std::uint32_t> m_order; // the refinement heap: indices into m_pairs
  FrameStats m_stats;
  Clock::time_point m_start;
  // Measured costs, smoothed over steps: they turn a time budget into node-pair shares and
  // hold back the contact writing. Start values are this machine's order of magnitude.
  double m_microsPerNodePair = 0.25;
  double m_writeMicros = 5.0;       // writing a decided pair's contacts
  double m_lateWriteMicros = 20.0;  // writing a cut pair's, after the queries
  double m_microsPerWholeUnit = 0.1;  // a whole pair's time per unit: for one never timed
  // Pairs of this step not queried yet, and queried but neither decided nor written.
  std::size_t m_unqueried = 0;
  std::size_t m_undecided = 0;
  bool m_binding = false;  // this step's budget is smaller than its pairs' expected cost
  double m_margin = 0.0;  // microseconds held back from a time budget (updateMargin)
  bool m_collecting = false;
  std::uint64_t m_step = 0;  // steps begun
  // Bodies with unusable poses this step (reused: no allocation in steady state).
  std::vector<const btCollisionObject*> m_badBodies;
  std::function<void(const BadPose&)> m_badPoseCallback;
  std::uint32_t m_badNamed = 0;
  BadPose m_badNamedPoses[FrameStats::kNamedBadPoses];
};

}  // namespace adb::detail
