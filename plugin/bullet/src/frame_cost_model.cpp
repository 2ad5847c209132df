// FrameCostModel: the scheduler's measured costs, smoothed over steps, and the time margin.
#include "frame_cost_model.h"

#include <algorithm>
#include <cmath>

#include "manifold_algorithm.h"

namespace adb::detail {
namespace {

// Smoothing of the measured costs (time per node pair, contact time per pair): recent steps
// count most, one odd step does not swing the next step's shares.
constexpr double kSmoothing = 0.2;
// The overshoot margin (updateMargin): its decay per step within budget, and its floor and
// cap. The floor covers what even a perfect estimate overruns by: the last query's clock
// interval and leaf pair, the spread of the cut pairs' contact writing; part of it is fixed
// (100 us took the pile's p99 at 16 and 12 ms from 0.15 % over the budget to within it).
// A decay of 15 % per step halves a spike's margin in 4 steps: at 1 % a step, one slow step
// on a busy machine left the next 70 under-spending the budget.
constexpr double kMarginDecay = 0.85;
constexpr double kMinMargin = 0.02;
constexpr double kMinMarginMicros = 100.0;
constexpr double kMaxMargin = 0.25;

// The margin's floor: 2 % of the budget and 100 us, at most the cap (small budgets).
double minMargin(double budgetMicros) {
  return std::min(kMinMargin * budgetMicros + kMinMarginMicros, kMaxMargin * budgetMicros);
}

}  // namespace

// A GJK pair costs far more per unit than a closed-form one: its own time is the better
// estimate once it has one.
double FrameCostModel::expectedWholeMicros(const ManifoldAlgorithm& algorithm) const {
  if (algorithm.lastMicros() > 0.0) return 1.25 * algorithm.lastMicros();
  return static_cast<double>(expectedCost(algorithm.lastWork(), kFirstWholeWork)) *
         m_microsPerWholeUnit;
}

double FrameCostModel::margin(double budgetMicros) const {
  return std::max(m_margin, minMargin(budgetMicros));
}

void FrameCostModel::measureQuery(std::uint64_t nodePairs, double seconds) {
  if (nodePairs < kFirstGrant || !(seconds > 0.0)) return;  // too short to measure
  const double perPair = seconds * 1e6 / static_cast<double>(nodePairs);
  m_microsPerNodePair += kSmoothing * (perPair - m_microsPerNodePair);
}

void FrameCostModel::measureWhole(std::uint64_t work, double micros) {
  if (work < kFirstGrant || !(micros > 0.0)) return;  // too short to measure
  m_microsPerWholeUnit += kSmoothing * (micros / static_cast<double>(work) - m_microsPerWholeUnit);
}

void FrameCostModel::measureWrites(double earlyMicros, std::uint32_t earlyPairs,
                                   double lateMicros, std::uint32_t latePairs) {
  if (earlyPairs > 0) {
    const double perPair = earlyMicros / static_cast<double>(earlyPairs);
    m_writeMicros += kSmoothing * (perPair - m_writeMicros);
  }
  if (latePairs > 0) {
    const double perPair = lateMicros / static_cast<double>(latePairs);
    m_lateWriteMicros += kSmoothing * (perPair - m_lateWriteMicros);
  }
}

// A step's whole overshoot is added to the margin, which decays by kMarginDecay per step that
// stays within. The overshoot (the last query's clock interval, contact writing slower than
// its average) varies from step to step: a margin that followed its mean would leave half the
// steps over budget; this one follows its peaks.
void FrameCostModel::updateMargin(double stepMicros, double budgetMicros) {
  if (std::isinf(budgetMicros)) return;
  const double over = stepMicros - budgetMicros;
  m_margin = over > 0.0 ? m_margin + over : m_margin * kMarginDecay;
  m_margin = std::clamp(m_margin, minMargin(budgetMicros), kMaxMargin * budgetMicros);
}

}  // namespace adb::detail
