// Internal: the step's figures (FrameStats) over its mesh-mesh pairs, and how a pair's stop
// reads in the reports. What the scheduler decided, counted; not part of deciding it.
#pragma once

#include <cstddef>

#include "adb/bullet/frame_budget.h"
#include "deferred_pair.h"

namespace adb::detail {

MeshPairReport::Outcome outcomeOf(StopReason stop);

/// A report of the pair for Dispatcher::lastMeshPairs.
MeshPairReport reportOf(const DeferredPair& pair);

/// Adds the mesh-mesh pairs of a step to its FrameStats one by one, then their means.
class MeshPairTally {
 public:
  /// The pair's need, confidence, completeness and outcome.
  void add(const DeferredPair& pair, FrameStats& stats);
  /// The means over the `pairs` added.
  void finish(std::size_t pairs, FrameStats& stats) const;

 private:
  double m_confidence = 0.0, m_completeness = 0.0;
};

}  // namespace adb::detail
