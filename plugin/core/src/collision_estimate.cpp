// The fitted collision estimate (adb/core/collision_estimate.h).
#include "adb/core/collision_estimate.h"

#include <algorithm>
#include <cmath>

namespace adb {
namespace {

// Sums of doubt are kept this far above 0 before their log: below it the doubt no longer tells
// states apart, and a deeper floor made a few near-certain states dominate the fit.
constexpr double kDoubtFloor = 1e-3;

double unit(double x) { return std::clamp(std::isnan(x) ? 0.0 : x, 0.0, 1.0); }

double logOf(double x) {
  return std::log(std::min(std::max(std::isnan(x) ? 0.0 : x, 0.0), 1e300) + kDoubtFloor);
}

// Fitted by `build/bin/adb-calibrate --rotations 30` (docs/probability-model.md gives the whole
// command and its tables) on the six generated models at 20k triangles, the sliver cylinder,
// the pipe bundle at 400 triangles and the robot arm, each against a copy of itself, and on
// pairs of different models (issue 43): the arm anywhere in the room, knot and gears, slivers
// and lock, the arm and the pipes, and the knot against gears a sixth its size; four quality
// settings under the defaults and one under the paper's rules. What decides a budget stop:
// the open pairs (how many), the expected collision cells, the fill of the open pairs first in
// the queue (what large flat triangles say where the cell model is blind) and how far the
// query got.
constexpr EstimateWeights kBudgetWeights{-3.6616, 0, 0, 0, 1.47694, 0, 0.625171, 0, 0.270669, -0.299348, 0, -0.739357, 0, 2.24807};
// P(the paper's answer is right) at quality stops: a model of collision itself answered worse
// than the paper's rule there (knot 16.7 % wrong against 9.1 %); this one keeps the rule's
// answer where it is right at least half the time and calibrates its confidence.
constexpr EstimateWeights kQualityWeights{-4.21203, -0.399716, -2.11761, 0.0882135, 2.23536, -1.21923, 1.45804, 5.2884, 0.230335, -0.614191, 0.0589662, 0.0779248, -1.0821, 1.90528};

// The budget model's monotone recalibration, fitted by the same run on the fit set's budget
// stops (pool-adjacent-violators, each case weighing 1): what the logistic model's features
// cannot express of its over- and under-confidence.
constexpr int kBudgetMapKnots = 15;
constexpr double kBudgetMapX[] = {0.136101, 0.270915, 0.352354, 0.464937, 0.594867, 0.690627, 0.755424, 0.798475, 0.838959, 0.870936, 0.89498, 0.915242, 0.936175, 0.963894, 0.99517};
constexpr double kBudgetMapY[] = {0.20065, 0.358444, 0.385219, 0.411913, 0.427809, 0.556652, 0.721358, 0.788813, 0.817487, 0.866041, 0.919166, 0.95797, 0.977953, 0.989159, 0.989159};

}  // namespace

std::array<double, kEstimateFeatures> estimateFeatures(const Evidence& e) {
  return {1.0,
          unit(e.frontierUnion),
          logOf(e.frontierDoubt + e.prunedDoubt),
          std::log1p(static_cast<double>(e.collisionPairs)),
          std::log1p(static_cast<double>(e.openPairs)),
          unit(e.bestOpen),
          logOf(e.expectedCells),
          e.quality && !e.reachedKMin ? 1.0 : 0.0,
          unit(e.blindUnion),
          std::log1p(static_cast<double>(e.blindPairs)),
          unit(e.rootFill),
          std::log1p(static_cast<double>(e.nodePairs)),
          unit(e.openFillUnion),
          unit(e.openFillMax)};
}

double logisticEstimate(const std::array<double, kEstimateFeatures>& f,
                        const EstimateWeights& w) {
  double z = 0.0;
  for (int i = 0; i < kEstimateFeatures; ++i) z += w[i] * f[i];
  if (std::isnan(z)) return 0.5;  // only NaN weights get here: no opinion
  // 1 / (1 + e^-z) without overflow for large |z|.
  const double p = z >= 0.0 ? 1.0 / (1.0 + std::exp(-z)) : std::exp(z) / (1.0 + std::exp(z));
  return std::clamp(p, 0.0, 1.0);
}

double monotoneMap(double p, const double* x, const double* y, int n) {
  if (n <= 0 || std::isnan(p)) return p;
  if (p <= x[0]) return y[0];
  if (p >= x[n - 1]) return y[n - 1];
  const int i = static_cast<int>(std::upper_bound(x, x + n, p) - x);  // x[i-1] < p <= x[i]
  const double span = x[i] - x[i - 1];
  const double t = span > 0.0 ? (p - x[i - 1]) / span : 1.0;
  return std::clamp(y[i - 1] + t * (y[i] - y[i - 1]), 0.0, 1.0);
}

double collisionProbability(const Evidence& e, const EstimateWeights& w) {
  return logisticEstimate(estimateFeatures(e), w);
}

double collisionProbability(const Evidence& e) {
  if (!e.quality) {
    return monotoneMap(collisionProbability(e, kBudgetWeights), kBudgetMapX, kBudgetMapY,
                       kBudgetMapKnots);
  }
  const double right = collisionProbability(e, kQualityWeights);
  return e.reachedKMin ? right : 1.0 - right;
}

}  // namespace adb
