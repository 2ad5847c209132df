// The probability model of the paper (§3.6): balls into bins and the collision lower bound.
//
// Balls into bins (Definition 6): u bins, v blue and w red balls, no bin gets two balls of
// one colour. X = number of bins with a ball of each colour is hypergeometric:
//   Pr[X = t] = C(v, t) C(u - v, w - t) / C(u, w)
// computed from a table of log n! for the first non-zero term and the term ratio
//   Pr[X = t+1] / Pr[X = t] = (v - t)(w - t) / ((t + 1)(u - v - w + t + 1))
// for the rest: exact to rounding for every u <= kMaxBins, no overflow, no NaN.
#pragma once

namespace adb {

/// Largest number of bins (cells) the model accepts: 32^3, the finest grid a tree allows.
inline constexpr int kMaxBins = 32 * 32 * 32;
/// The paper bounds x in Eq. 3 by a small number (10): the maximum sits at small x.
inline constexpr int kMaxCollisionCells = 10;

/// Pr[X >= x] for x = 1..xMax, written to tailOut[0..xMax-1]. Arguments are clamped to
/// 0 <= v, w <= u <= kMaxBins; every output is in [0, 1]. xMax <= kMaxCollisionCells.
void hypergeometricTail(int u, int v, int w, int xMax, double* tailOut);

/// Pr[X >= x] for one x >= 0 (any x; 1 for x <= 0). Slower: for tests and tables.
double probabilityAtLeast(int u, int v, int w, int x);

/// Eq. 3: max over 1 <= x <= min(v, w, kMaxCollisionCells) of Pr[X >= x] (1 - (1 - lb)^x),
/// the paper's lower bound for Pr[the polygon sets intersect]. lb is clamped to [0, 1].
/// Returns 0 when v or w is 0. Always in [0, 1].
double collisionLowerBound(int s, int sA, int sB, double lb);

/// The lower bound of Eq. 3 and the upper estimate Pr[X >= 1] (under the model, polygons
/// intersect only inside a collision cell) from one evaluation of the tail.
struct CollisionEstimate {
  double lower = 0.0;  ///< Eq. 3
  double upper = 0.0;  ///< Pr[X >= 1]
};
CollisionEstimate estimateCollision(int s, int sA, int sB, double lb);

/// Whether Eq. 3 (collisionLowerBound(s, sA, sB, lb)) could exceed `threshold`: false only
/// where it cannot, so a caller that evaluates Eq. 3 only where this is true accepts exactly
/// the pairs it would accept evaluating it everywhere. Eq. 3 > threshold needs an x <=
/// min(sA, sB, 10) with 1 - (1 - lb)^x > threshold (computed as Eq. 3 computes it) and
/// Pr[X >= x] > threshold at the smallest such x; the tail is bounded by Markov (mu / x) and
/// Cantelli (sigma^2 / (sigma^2 + (x - mu)^2)) with a margin far above Eq. 3's rounding.
/// On the knot's nodePairCost/adb benchmark (callgrind with -g) the tail's part costs 68
/// instructions a call, Eq. 3 335 (docs/probability-model.md section 6 has the command).
bool collisionLowerBoundCouldExceed(int s, int sA, int sB, double lb, double threshold);

/// The pre-test in two parts, for a caller that tests many pairs at one depth term: the
/// smallest x <= kMaxCollisionCells with 1 - (1 - lb)^x > threshold (kMaxCollisionCells + 1
/// if none), then for a pair with min(sA, sB) >= that x, the tail's part. The pair could pass
/// exactly when both do.
int smallestPassingCells(double lb, double threshold);
bool collisionTailCouldExceed(int s, int sA, int sB, int x, double threshold);

/// Paper §3.6.3: LB = (dA + dB) / (dmaxA + dmaxB), 0 when both trees are single leaves.
double cellIntersectionBound(int depthA, int depthB, int maxDepthA, int maxDepthB);

}  // namespace adb
