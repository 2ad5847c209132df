// Internal: what the scheduler's work costs, measured step after step: the time of a node
// pair, of a whole pair's unit of work and of writing a pair's contacts, and the margin held
// back from a time budget. It turns a time budget into node-pair shares; the policy that
// spends them is FrameScheduler's.
#pragma once

#include <cstdint>

namespace adb {
class ManifoldAlgorithm;
}

namespace adb::detail {

/// The smallest first grant of a mesh-mesh pair (a few levels of both trees); also the least
/// work a measurement needs to count (shorter ones are mostly the clock's interval).
inline constexpr std::uint64_t kFirstGrant = 256;
/// What a whole pair (mesh against a convex shape, a plane, ...) never run is expected to
/// cost: a few nodes and triangles, so that a tight budget is not overrun at first contact.
inline constexpr std::uint64_t kFirstWholeWork = 128;

/// What a pair is expected to cost: its last cost and a quarter more (bodies settling into
/// each other touch more triangles step by step), at least `least`.
inline std::uint64_t expectedCost(std::uint64_t last, std::uint64_t least) {
  return last + last / 4 > least ? last + last / 4 : least;
}

class FrameCostModel {
 public:
  double microsPerNodePair() const { return m_microsPerNodePair; }
  /// Writing a decided pair's contacts, and a cut pair's (after the queries: more witnesses,
  /// its plausible contacts).
  double writeMicros() const { return m_writeMicros; }
  double lateWriteMicros() const { return m_lateWriteMicros; }
  /// A whole pair's expected time: its last and a quarter more, or, never timed, its expected
  /// work at the measured time per unit.
  double expectedWholeMicros(const ManifoldAlgorithm& algorithm) const;
  /// Microseconds held back from a time budget of `budgetMicros` for the step's overshoot.
  double margin(double budgetMicros) const;

  /// A mesh-mesh query did `nodePairs` in `seconds`.
  void measureQuery(std::uint64_t nodePairs, double seconds);
  /// A whole pair did `work` units in `micros`.
  void measureWhole(std::uint64_t work, double micros);
  /// The step wrote `earlyPairs` decided pairs' contacts in `earlyMicros`, and `latePairs`
  /// cut pairs' in `lateMicros`.
  void measureWrites(double earlyMicros, std::uint32_t earlyPairs, double lateMicros,
                     std::uint32_t latePairs);
  /// After a step of `stepMicros` under a time budget of `budgetMicros` (infinite: none).
  void updateMargin(double stepMicros, double budgetMicros);

 private:
  // Start values are this machine's order of magnitude; measurements replace them.
  double m_microsPerNodePair = 0.25;
  double m_writeMicros = 5.0;
  double m_lateWriteMicros = 20.0;
  double m_microsPerWholeUnit = 0.1;  // a whole pair's time per unit: for one never timed
  double m_margin = 0.0;
};

}  // namespace adb::detail
