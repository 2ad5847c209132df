// Internal: FrameScheduler, which collects the mesh-mesh pairs of a step while Bullet
// dispatches and then spends the step's budget across them (policy: adb/bullet/frame_budget.h).
#pragma once

#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <LinearMath/btTransform.h>

#include <chrono>
#include <cstdint>
#include <vector>

#include "adb/bullet/frame_budget.h"
#include "adb/core/query.h"

namespace adb {
class MeshMeshAlgorithm;
}

namespace adb::detail {

/// A mesh-mesh pair noted during the dispatch: enough to rebuild Bullet's wrappers and
/// result afterwards (the dispatch's own live on its stack), and the pair's scheduling state.
struct DeferredPair {
  MeshMeshAlgorithm* algorithm;
  const btCollisionObject* object0;
  const btCollisionObject* object1;
  btTransform transform0, transform1;  // the wrappers' world transforms, kept by value
  int partId0, index0, partId1, index1;
  // Scheduling state of this step.
  std::uint64_t grant = 0;     // node pairs granted this step (all its queries)
  double confidence = 0.0;     // see FrameStats::meanConfidence
  StopReason stop = StopReason::Completed;
  bool written = false;        // its contacts are in its manifold

  /// Completed or stopped on quality: nothing left to refine.
  bool decided() const {
    return stop == StopReason::Completed || stop == StopReason::QualityReached;
  }
};

class FrameScheduler {
 public:
  /// Starts a step: pairs noted from now on are scheduled by run().
  void begin();
  bool collecting() const { return m_collecting; }
  void defer(const DeferredPair& pair) { m_pairs.push_back(pair); }
  /// Spends the budget across the noted pairs, writes their manifolds, ends the step.
  void run(const FrameSettings& settings);
  const FrameStats& stats() const { return m_stats; }
  /// Notes a body with an unusable pose for this step: its report the first time this step
  /// (for the dispatcher's callback), nullptr when already noted.
  const BadPose* noteBadPose(const btCollisionObject* body, PoseDefect defect);

 private:
  using Clock = std::chrono::steady_clock;

  void firstPass(const FrameSettings& settings);
  void refine(const FrameSettings& settings);
  /// Runs one query of `pair`; returns the work it did (node pairs and triangle tests).
  std::uint64_t query(DeferredPair& pair, std::uint64_t grant, double micros,
                      const FrameSettings& settings, bool resume);
  double writePair(DeferredPair& pair, const FrameSettings& settings);
  void writeContacts(const FrameSettings& settings);
  std::uint64_t nodePairsLeft(const FrameSettings& settings) const;
  double microsLeft(const FrameSettings& settings) const;
  void updateMargin(const FrameSettings& settings);
  std::uint64_t share(const FrameSettings& settings, std::uint64_t waiting) const;

  std::vector<DeferredPair> m_pairs;  // reused: no allocation in steady state
  std::vector<std::uint32_t> m_order; // the refinement heap: indices into m_pairs
  FrameStats m_stats;
  Clock::time_point m_start;
  // Measured costs, smoothed over steps: they turn a time budget into node-pair shares and
  // hold back the contact writing. Start values are this machine's order of magnitude.
  double m_microsPerNodePair = 0.25;
  double m_writeMicros = 5.0;       // writing a decided pair's contacts
  double m_lateWriteMicros = 20.0;  // writing a cut pair's, after the queries
  // Pairs of this step not queried yet, and queried but neither decided nor written.
  std::size_t m_unqueried = 0;
  std::size_t m_undecided = 0;
  double m_margin = 0.0;  // microseconds held back from a time budget (updateMargin)
  bool m_collecting = false;
  // Bodies with unusable poses this step (reused: no allocation in steady state).
  std::vector<const btCollisionObject*> m_badBodies;
  BadPose m_badPose;  // the last one noted
  std::uint32_t m_badNamed = 0;
  BadPose m_badNamedPoses[FrameStats::kNamedBadPoses];
};

}  // namespace adb::detail
