// The balls-into-bins model (paper §3.6.1) and Eq. 3, against brute-force enumeration of bin
// placements (small u) and Monte Carlo (large u), plus edge values.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>

#include "adb/core/probability.h"
#include "test_support.h"

namespace adb {
namespace {

// Enumeration is exact up to rounding of the sums: a few ulps of 1.
constexpr double kEnumerationTolerance = 1e-12;

// All placements: blue balls on a v-subset, red on a w-subset of u bins, each equally likely.
// Returns Pr[X >= x] for x = 0..u.
std::vector<double> enumerateTail(int u, int v, int w) {
  std::vector<double> count(u + 2, 0.0);
  double total = 0.0;
  for (unsigned blue = 0; blue < (1u << u); ++blue) {
    if (__builtin_popcount(blue) != v) continue;
    for (unsigned red = 0; red < (1u << u); ++red) {
      if (__builtin_popcount(red) != w) continue;
      count[__builtin_popcount(blue & red)] += 1.0;
      total += 1.0;
    }
  }
  std::vector<double> tail(u + 2, 0.0);
  for (int x = u; x >= 0; --x) tail[x] = tail[x + 1] + count[x] / total;
  return tail;
}

TEST(ProbabilityModel, MatchesEnumerationForSmallBins) {
  for (int u = 0; u <= 9; ++u) {
    for (int v = 0; v <= u; ++v) {
      for (int w = 0; w <= u; ++w) {
        const auto expected = enumerateTail(u, v, w);
        double tail[kMaxCollisionCells];
        hypergeometricTail(u, v, w, kMaxCollisionCells, tail);
        for (int x = 1; x <= kMaxCollisionCells; ++x) {
          const double want = x <= u ? expected[x] : 0.0;
          EXPECT_NEAR(tail[x - 1], want, kEnumerationTolerance) << u << " " << v << " " << w
                                                                << " x=" << x;
          EXPECT_NEAR(probabilityAtLeast(u, v, w, x), want, kEnumerationTolerance);
        }
      }
    }
  }
}

TEST(ProbabilityModel, MatchesMonteCarloForLargeBins) {
  std::mt19937_64 rng(test::kSeed);
  struct Case {
    int u, v, w;
  };
  const Case cases[] = {{512, 20, 30}, {512, 100, 200}, {512, 3, 400}, {300, 40, 40},
                        {4096, 64, 128}};
  constexpr int kSamples = 20000;
  for (const Case& c : cases) {
    std::vector<int> bins(c.u);
    std::iota(bins.begin(), bins.end(), 0);
    std::vector<int> hits(kMaxCollisionCells + 2, 0);
    std::vector<char> blue(c.u);
    for (int s = 0; s < kSamples; ++s) {
      // Partial Fisher-Yates: the first v bins are blue, then an independent draw for red.
      std::fill(blue.begin(), blue.end(), 0);
      for (int i = 0; i < c.v; ++i) {
        std::swap(bins[i], bins[std::uniform_int_distribution<int>(i, c.u - 1)(rng)]);
        blue[bins[i]] = 1;
      }
      int both = 0;
      for (int i = 0; i < c.w; ++i) {
        std::swap(bins[i], bins[std::uniform_int_distribution<int>(i, c.u - 1)(rng)]);
        both += blue[bins[i]];
      }
      for (int x = 1; x <= std::min(both, kMaxCollisionCells); ++x) ++hits[x];
    }
    double tail[kMaxCollisionCells];
    hypergeometricTail(c.u, c.v, c.w, kMaxCollisionCells, tail);
    for (int x = 1; x <= kMaxCollisionCells; ++x) {
      const double p = tail[x - 1];
      const double observed = static_cast<double>(hits[x]) / kSamples;
      // Five standard errors of a binomial proportion (plus a floor for p near 0 or 1).
      const double tol = 5.0 * std::sqrt(p * (1.0 - p) / kSamples) + 1e-3;
      EXPECT_NEAR(observed, p, tol) << c.u << " " << c.v << " " << c.w << " x=" << x;
    }
  }
}

TEST(ProbabilityModelEdge, NoBallsOfOneColourMeansNoCollisionCell) {
  double tail[kMaxCollisionCells];
  hypergeometricTail(512, 0, 300, kMaxCollisionCells, tail);
  for (double t : tail) EXPECT_EQ(t, 0.0);
  hypergeometricTail(512, 300, 0, kMaxCollisionCells, tail);
  for (double t : tail) EXPECT_EQ(t, 0.0);
  EXPECT_EQ(collisionLowerBound(512, 0, 300, 0.9), 0.0);
  EXPECT_EQ(estimateCollision(512, 300, 0, 0.9).upper, 0.0);
}

TEST(ProbabilityModelEdge, AllBinsFilledMeansCertainty) {
  // v = w = u: every bin gets both colours, X = u.
  double tail[kMaxCollisionCells];
  hypergeometricTail(512, 512, 512, kMaxCollisionCells, tail);
  for (double t : tail) EXPECT_DOUBLE_EQ(t, 1.0);
  // v + w > u forces at least v + w - u shared bins.
  hypergeometricTail(512, 300, 300, kMaxCollisionCells, tail);
  for (double t : tail) EXPECT_DOUBLE_EQ(t, 1.0);
  EXPECT_DOUBLE_EQ(collisionLowerBound(512, 512, 512, 1.0), 1.0);
}

TEST(ProbabilityModelEdge, LargestGridsStayFiniteAndInRange) {
  std::mt19937_64 rng(test::kSeed);
  for (int u : {512, 4096, kMaxBins}) {
    for (int trial = 0; trial < 2000; ++trial) {
      const int v = std::uniform_int_distribution<int>(0, u)(rng);
      const int w = std::uniform_int_distribution<int>(0, u)(rng);
      double tail[kMaxCollisionCells];
      hypergeometricTail(u, v, w, kMaxCollisionCells, tail);
      for (int x = 0; x < kMaxCollisionCells; ++x) {
        ASSERT_TRUE(tail[x] >= 0.0 && tail[x] <= 1.0) << u << " " << v << " " << w;
        if (x > 0) {
          ASSERT_LE(tail[x], tail[x - 1] + 1e-15);  // a tail never grows with x
        }
      }
      const double lb = std::uniform_real_distribution<double>(0.0, 1.0)(rng);
      const CollisionEstimate e = estimateCollision(u, v, w, lb);
      ASSERT_TRUE(e.lower >= 0.0 && e.lower <= 1.0);
      ASSERT_LE(e.lower, e.upper + 1e-15);  // Eq. 3 never exceeds Pr[X >= 1]
    }
  }
}

TEST(ProbabilityModelEdge, OutOfRangeArgumentsAreClamped) {
  EXPECT_EQ(collisionLowerBound(-5, 3, 3, 0.5), 0.0);
  EXPECT_EQ(collisionLowerBound(10, -1, 3, 0.5), 0.0);
  const double clamped = collisionLowerBound(kMaxBins * 2, kMaxBins * 2, kMaxBins * 2, 2.0);
  EXPECT_DOUBLE_EQ(clamped, 1.0);
  EXPECT_EQ(collisionLowerBound(100, 50, 50, std::nan("")), 0.0);
}

TEST(ProbabilityEq3, GrowsWithTheCellBoundAndTheCounts) {
  double previous = 0.0;
  for (double lb = 0.0; lb <= 1.0; lb += 0.05) {
    const double p = collisionLowerBound(300, 60, 60, lb);
    EXPECT_GE(p, previous - 1e-15);
    previous = p;
  }
  previous = 0.0;
  for (int v = 0; v <= 300; v += 10) {
    const double p = collisionLowerBound(300, v, 60, 0.3);
    EXPECT_GE(p, previous - 1e-15);
    previous = p;
  }
}

TEST(ProbabilityEq3, EqualsTheMaximumOverX) {
  // Direct evaluation of Eq. 3 from probabilityAtLeast.
  const int s = 200, sa = 25, sb = 40;
  const double lb = 0.2;
  double best = 0.0;
  for (int x = 1; x <= 10; ++x) {
    best = std::max(best, probabilityAtLeast(s, sa, sb, x) * (1.0 - std::pow(1.0 - lb, x)));
  }
  EXPECT_NEAR(collisionLowerBound(s, sa, sb, lb), best, 1e-12);
}

TEST(ProbabilityCellBound, DepthRatio) {
  EXPECT_DOUBLE_EQ(cellIntersectionBound(3, 5, 10, 10), 0.4);
  EXPECT_DOUBLE_EQ(cellIntersectionBound(0, 0, 0, 0), 0.0);  // two single-leaf trees
  EXPECT_DOUBLE_EQ(cellIntersectionBound(10, 10, 10, 10), 1.0);
}

// The pre-test the traversal runs before Eq. 3 (collisionLowerBoundCouldExceed) never says
// "cannot" where Eq. 3 exceeds the threshold: exhaustively over small bins, every depth ratio
// of trees up to 60 levels deep in total and the thresholds users set, and over a million
// random triples up to the largest grid. It must also reject most pairs at a high threshold,
// or it would save nothing.
const double kThresholds[] = {0.0, 0.1, 0.5, 0.9, 0.99, 0.999};

TEST(ProbabilityEq3PreTest, NeverRejectsAnAcceptanceOverSmallBins) {
  long checked = 0, rejected = 0, wrong = 0;
  for (int s = 1; s <= 24; ++s) {
    for (int sa = 0; sa <= s; ++sa) {
      for (int sb = 0; sb <= s; ++sb) {
        for (int total : {2, 5, 10, 20, 40, 60}) {
          for (int depth = 0; depth <= total; ++depth) {
            const double lb = cellIntersectionBound(depth, 0, total, 0);
            const double eq3 = collisionLowerBound(s, sa, sb, lb);
            for (double threshold : kThresholds) {
              ++checked;
              if (collisionLowerBoundCouldExceed(s, sa, sb, lb, threshold)) continue;
              ++rejected;
              if (eq3 > threshold) ++wrong;
            }
          }
        }
      }
    }
  }
  EXPECT_EQ(wrong, 0) << "of " << checked;
  EXPECT_GT(rejected, checked / 3);  // measured: 47 %, thresholds of 0 included
}

TEST(ProbabilityEq3PreTest, NeverRejectsAnAcceptanceOverAMillionRandomTriples) {
  std::mt19937_64 rng(test::kSeed);
  std::uniform_int_distribution<int> bins(1, kMaxBins);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  long rejectedAt99 = 0, wrong = 0;
  const int trials = 1000000;
  for (int trial = 0; trial < trials; ++trial) {
    const int s = trial % 2 == 0 ? bins(rng) : 1 + static_cast<int>(rng() % 200);
    // Densities spread on a log scale: most pairs in a traversal are sparse.
    const auto count = [&] {
      return std::min(s, static_cast<int>(std::pow(static_cast<double>(s) + 1.0, unit(rng))));
    };
    const int sa = count(), sb = count();
    const double lb = unit(rng);
    const double threshold = kThresholds[trial % 6];
    if (collisionLowerBoundCouldExceed(s, sa, sb, lb, threshold)) continue;
    if (threshold == 0.99) ++rejectedAt99;
    if (collisionLowerBound(s, sa, sb, lb) > threshold) ++wrong;
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(rejectedAt99, trials / 6 * 7 / 10);  // measured: 78 %
}

}  // namespace
}  // namespace adb
