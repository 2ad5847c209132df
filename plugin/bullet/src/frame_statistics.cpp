// The step's figures over its mesh-mesh pairs.
#include "frame_statistics.h"

#include <algorithm>

#include "mesh_mesh_algorithm.h"

namespace adb::detail {

MeshPairReport::Outcome outcomeOf(StopReason stop) {
  if (stop == StopReason::Completed || stop == StopReason::WitnessesFull) {
    return MeshPairReport::Outcome::Exact;
  }
  return stop == StopReason::QualityReached ? MeshPairReport::Outcome::Quality
                                            : MeshPairReport::Outcome::Cut;
}

MeshPairReport reportOf(const DeferredPair& pair) {
  return MeshPairReport{pair.object0, pair.object1, outcomeOf(pair.stop), pair.confidence,
                        pair.completeness};
}

void MeshPairTally::add(const DeferredPair& pair, FrameStats& stats) {
  stats.neededNodePairs += pair.meshMesh().needed();
  stats.fromScratchNodePairs += pair.meshMesh().neededFromScratch();
  m_confidence += pair.confidence;
  stats.worstConfidence = std::min(stats.worstConfidence, pair.confidence);
  m_completeness += pair.completeness;
  stats.worstCompleteness = std::min(stats.worstCompleteness, pair.completeness);
  switch (outcomeOf(pair.stop)) {
    case MeshPairReport::Outcome::Exact: ++stats.exactPairs; break;
    case MeshPairReport::Outcome::Quality: ++stats.qualityPairs; break;
    case MeshPairReport::Outcome::Cut: ++stats.cutPairs; break;
  }
}

void MeshPairTally::finish(std::size_t pairs, FrameStats& stats) const {
  if (pairs == 0) return;
  stats.meanConfidence = m_confidence / static_cast<double>(pairs);
  stats.meanCompleteness = m_completeness / static_cast<double>(pairs);
}

}  // namespace adb::detail
