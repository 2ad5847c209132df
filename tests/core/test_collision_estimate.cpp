// The collision estimate (adb/core/collision_estimate.h): a probability for any evidence, and
// monotone in the evidence for a collision. Its calibration is tested through queries in
// test_query_adb.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "adb/core/collision_estimate.h"

namespace adb {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Evidence randomEvidence(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> logSum(-12.0, 8.0);
  Evidence e;
  e.frontierUnion = unit(rng);
  e.frontierDoubt = std::exp(logSum(rng));
  e.prunedDoubt = unit(rng) < 0.5 ? 0.0 : std::exp(logSum(rng));
  e.bestOpen = e.frontierUnion * unit(rng);
  e.openPairs = static_cast<std::uint32_t>(std::exp(logSum(rng) + 4.0));
  e.collisionPairs = static_cast<std::uint32_t>(unit(rng) * 20.0);
  e.expectedCells = std::exp(logSum(rng));
  e.blindPairs = static_cast<std::uint32_t>(std::exp(logSum(rng) + 2.0));
  e.blindUnion = e.blindPairs > 0 ? unit(rng) : 0.0;
  e.rootFill = unit(rng);
  e.nodePairs = static_cast<std::uint64_t>(std::exp(logSum(rng) + 6.0));
  return e;
}

TEST(CollisionEstimate, AnyEvidenceGivesAProbability) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 20000; ++i) {
    const double p = collisionProbability(randomEvidence(rng));
    ASSERT_TRUE(p >= 0.0 && p <= 1.0) << p;
  }
  for (double x : {0.0, 1.0, -1.0, 2.0, kInf, -kInf, kNaN, 1e308, -1e308}) {
    Evidence e;
    e.frontierUnion = e.frontierDoubt = e.prunedDoubt = e.bestOpen = e.expectedCells = x;
    e.blindUnion = e.rootFill = x;
    e.openPairs = e.collisionPairs = e.blindPairs = 0xFFFFFFFFu;
    e.nodePairs = ~std::uint64_t{0};
    const double p = collisionProbability(e);
    EXPECT_TRUE(p >= 0.0 && p <= 1.0) << "evidence " << x << " gave " << p;
    for (double f : estimateFeatures(e)) EXPECT_TRUE(std::isfinite(f)) << "evidence " << x;
  }
}

// More evidence for a collision (a larger union, doubt, pruned doubt, best open bound, more
// accepted pairs, a larger union of the blind pairs' keys or a fuller overlap of the roots)
// never lowers the estimate: with the fitted weights, and with any weights
// whose evidence terms are >= 0 (what the fit guarantees).
TEST(CollisionEstimate, MoreEvidenceNeverLowersTheEstimate) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> normal(0.0, 2.0);
  for (int trial = 0; trial < 200; ++trial) {
    EstimateWeights w{};
    const bool fitted = trial == 0;
    for (int i = 0; i < kEstimateFeatures; ++i) {
      w[i] = kEvidenceFeature[i] ? std::abs(normal(rng)) : normal(rng);
    }
    const auto p = [&](const Evidence& e) {
      return fitted ? collisionProbability(e) : collisionProbability(e, w);
    };
    for (int i = 0; i < 200; ++i) {
      const Evidence base = randomEvidence(rng);
      const double p0 = p(base);
      Evidence more = base;
      more.frontierUnion = std::min(1.0, base.frontierUnion + 0.1);
      more.bestOpen = std::min(more.frontierUnion, base.bestOpen + 0.05);
      EXPECT_GE(p(more), p0);
      more = base;
      more.frontierDoubt *= 3.0;
      EXPECT_GE(p(more), p0);
      more = base;
      more.prunedDoubt += 0.5;
      EXPECT_GE(p(more), p0);
      more = base;
      more.collisionPairs += 1;
      EXPECT_GE(p(more), p0);
      more = base;
      more.expectedCells *= 2.0;
      EXPECT_GE(p(more), p0);
      more = base;
      more.blindUnion = std::min(1.0, base.blindUnion + 0.1);
      EXPECT_GE(p(more), p0);
      more = base;
      more.rootFill = std::min(1.0, base.rootFill + 0.1);
      EXPECT_GE(p(more), p0);
    }
  }
}

// At a quality stop the estimate is the probability that the paper's answer is right: a
// queue emptied by pruning with little pruned doubt says "no" with confidence, k_min reached
// with many accepted pairs and doubt says "collision".
TEST(CollisionEstimate, QualityStopsLeanTowardsThePapersAnswer) {
  Evidence emptied;
  emptied.quality = true;
  emptied.reachedKMin = false;
  emptied.prunedDoubt = 0.01;
  emptied.expectedCells = 0.01;
  EXPECT_LT(collisionProbability(emptied), 0.1);
  Evidence reached;
  reached.quality = true;
  reached.reachedKMin = true;
  reached.collisionPairs = 10;
  reached.openPairs = 40;
  reached.frontierDoubt = 30.0;
  reached.frontierUnion = 0.999;
  reached.bestOpen = 0.995;
  reached.expectedCells = 200.0;
  EXPECT_GT(collisionProbability(reached), 0.5);
  for (double x : {0.0, 1.0, kNaN, kInf}) {
    reached.frontierDoubt = reached.expectedCells = x;
    const double p = collisionProbability(reached);
    EXPECT_TRUE(p >= 0.0 && p <= 1.0) << x;
  }
}

TEST(CollisionEstimate, WeightsTurnFeaturesIntoALogisticModel) {
  // sigmoid(w . f) with the features as documented: known values.
  Evidence e;
  e.frontierUnion = 0.5;
  e.frontierDoubt = 1.0 - 1e-3;  // log(doubt + 1e-3) = 0
  e.collisionPairs = 0;          // log1p = 0
  e.openPairs = 0;
  e.bestOpen = 0.25;
  EXPECT_NEAR(collisionProbability(e, EstimateWeights{-1.0, 2, 7, 5, 3, 0, 0}), 0.5, 1e-9);
  EXPECT_NEAR(collisionProbability(e, EstimateWeights{std::log(3.0), 0, 0, 0, 0, 0, 0}), 0.75,
              1e-12);
  EXPECT_NEAR(collisionProbability(e, EstimateWeights{0, 0, 0, 0, 0, 4.0 * std::log(9.0), 0}), 0.9,
              1e-9);
  // The features the fitted weights use: counts through log(1 + n), expected cells through
  // log(x + 1e-3). Each alone: sigmoid(w * feature) against a hand-computed value.
  e.collisionPairs = 2;  // log 3
  EXPECT_NEAR(collisionProbability(e, EstimateWeights{0, 0, 0, 1, 0, 0, 0}), 0.75, 1e-9);
  e.collisionPairs = 0;
  e.openPairs = 8;  // log 9
  EXPECT_NEAR(collisionProbability(e, EstimateWeights{0, 0, 0, 0, 1, 0, 0}), 0.9, 1e-9);
  EXPECT_NEAR(collisionProbability(e, EstimateWeights{0, 0, 0, 0, -1, 0, 0}), 0.1, 1e-9);
  e.openPairs = 0;
  e.expectedCells = 4.0 - 1e-3;  // log 4
  EXPECT_NEAR(collisionProbability(e, EstimateWeights{0, 0, 0, 0, 0, 0, 1}), 0.8, 1e-9);
  e.frontierDoubt = 0.5 - 1e-3;  // the doubt's log: log 0.5, so sigmoid(-log 2) = 1/3
  EXPECT_NEAR(collisionProbability(e, EstimateWeights{0, 0, 1, 0, 0, 0, 0}), 1.0 / 3.0, 1e-9);
  EXPECT_NEAR(collisionProbability(e, EstimateWeights{0, 1e6, 0, 0, 0, 0}), 1.0, 1e-12);
  EXPECT_NEAR(collisionProbability(e, EstimateWeights{0, -1e6, 0, 0, 0, 0}), 0.0, 1e-12);
  // What the cell model is blind to (issue 43): the blind pairs' union and count, the roots'
  // fill, the work done.
  Evidence blind;
  blind.frontierDoubt = 1.0 - 1e-3;
  blind.blindUnion = 0.75;
  blind.blindPairs = 8;  // log 9
  blind.rootFill = 0.5;
  blind.nodePairs = 2;   // log 3
  const auto only = [](int i, double w) {
    EstimateWeights weights{};
    weights[i] = w;
    return weights;
  };
  EXPECT_NEAR(collisionProbability(blind, only(8, 4.0 * std::log(3.0) / 3.0)), 0.75, 1e-9);
  EXPECT_NEAR(collisionProbability(blind, only(9, 1.0)), 0.9, 1e-9);
  EXPECT_NEAR(collisionProbability(blind, only(10, 2.0 * std::log(3.0))), 0.75, 1e-9);
  EXPECT_NEAR(collisionProbability(blind, only(11, 1.0)), 0.75, 1e-9);
}

// The budget model's recalibration: piecewise linear through its knots, held beyond them,
// non-decreasing, and the identity without knots.
TEST(CollisionEstimate, TheMonotoneMapInterpolatesItsKnots) {
  const double x[] = {0.1, 0.5, 0.9};
  const double y[] = {0.2, 0.4, 0.95};
  EXPECT_DOUBLE_EQ(monotoneMap(0.0, x, y, 3), 0.2);
  EXPECT_DOUBLE_EQ(monotoneMap(0.1, x, y, 3), 0.2);
  EXPECT_NEAR(monotoneMap(0.3, x, y, 3), 0.3, 1e-12);
  EXPECT_NEAR(monotoneMap(0.7, x, y, 3), 0.675, 1e-12);
  EXPECT_DOUBLE_EQ(monotoneMap(1.0, x, y, 3), 0.95);
  EXPECT_DOUBLE_EQ(monotoneMap(0.37, x, y, 0), 0.37);
  double last = 0.0;
  for (double p = 0.0; p <= 1.0; p += 0.001) {
    const double m = monotoneMap(p, x, y, 3);
    EXPECT_GE(m, last);
    last = m;
  }
}

}  // namespace
}  // namespace adb
