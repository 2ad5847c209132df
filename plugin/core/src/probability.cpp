// Balls-into-bins probabilities (paper §3.6.1-3.6.3), exact in double for u <= kMaxBins.
#include "adb/core/probability.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace adb {
namespace {

// log n! for n = 0..kMaxBins, built once (thread-safe static initialisation), 256 KiB.
const std::vector<double>& logFactorials() {
  static const std::vector<double> table = [] {
    std::vector<double> t(kMaxBins + 1, 0.0);
    for (int n = 1; n <= kMaxBins; ++n) t[n] = t[n - 1] + std::log(static_cast<double>(n));
    return t;
  }();
  return table;
}

double logChoose(const std::vector<double>& lf, int n, int k) { return lf[n] - lf[k] - lf[n - k]; }

struct Bins {
  int u, v, w;
};

Bins clampBins(int u, int v, int w) {
  u = std::clamp(u, 0, kMaxBins);
  return {u, std::clamp(v, 0, u), std::clamp(w, 0, u)};
}

// Pr[X = t] for t = t0, t0+1, ..., into `terms` (terms[i] = Pr[X = t0 + i]) while t < xMax.
// Returns t0 = max(0, v + w - u), the smallest t with Pr[X = t] > 0.
int pointProbabilities(const Bins& b, int xMax, double* terms) {
  const auto& lf = logFactorials();
  const int t0 = std::max(0, b.v + b.w - b.u);
  const int tMax = std::min(b.v, b.w);
  if (t0 >= xMax) return t0;
  double p = std::exp(logChoose(lf, b.v, t0) + logChoose(lf, b.u - b.v, b.w - t0) -
                      logChoose(lf, b.u, b.w));
  for (int t = t0; t < xMax; ++t) {
    terms[t - t0] = t <= tMax ? p : 0.0;
    if (t >= tMax) {
      p = 0.0;
      continue;
    }
    // The denominator is >= 1 for t >= t0: (u - v - w + t + 1) >= 1 exactly when t >= t0.
    p *= static_cast<double>(b.v - t) * (b.w - t) /
         (static_cast<double>(t + 1) * (b.u - b.v - b.w + t + 1));
  }
  return t0;
}

}  // namespace

void hypergeometricTail(int u, int v, int w, int xMax, double* tailOut) {
  xMax = std::clamp(xMax, 0, kMaxCollisionCells);
  const Bins b = clampBins(u, v, w);
  std::array<double, kMaxCollisionCells> terms{};
  const int t0 = pointProbabilities(b, xMax, terms.data());
  // Pr[X >= x] = 1 - sum_{t < x} Pr[X = t]; terms below t0 are zero.
  double below = 0.0;
  for (int x = 1; x <= xMax; ++x) {
    const int t = x - 1;
    if (t >= t0) below += terms[t - t0];
    tailOut[x - 1] = (b.v == 0 || b.w == 0) ? 0.0 : std::clamp(1.0 - below, 0.0, 1.0);
  }
}

double probabilityAtLeast(int u, int v, int w, int x) {
  if (x <= 0) return 1.0;
  const Bins b = clampBins(u, v, w);
  if (x > std::min(b.v, b.w)) return 0.0;
  const auto& lf = logFactorials();
  // Sum the upper tail directly (all terms positive: no cancellation for small tails).
  double sum = 0.0;
  for (int t = std::max(x, b.v + b.w - b.u); t <= std::min(b.v, b.w); ++t) {
    sum += std::exp(logChoose(lf, b.v, t) + logChoose(lf, b.u - b.v, b.w - t) -
                    logChoose(lf, b.u, b.w));
  }
  return std::clamp(sum, 0.0, 1.0);
}

double collisionLowerBound(int s, int sA, int sB, double lb) {
  return estimateCollision(s, sA, sB, lb).lower;
}

CollisionEstimate estimateCollision(int s, int sA, int sB, double lb) {
  const Bins b = clampBins(s, sA, sB);
  const int xMax = std::min({b.v, b.w, kMaxCollisionCells});
  if (xMax <= 0) return {};
  lb = std::isnan(lb) ? 0.0 : std::clamp(lb, 0.0, 1.0);
  std::array<double, kMaxCollisionCells> tail{};
  if (b.v + b.w - b.u >= xMax) {
    // At least v + w - u bins must get both colours: every tail up to xMax is 1 (a common
    // case for dense, deep node pairs; it skips the exp and the sums).
    tail.fill(1.0);
  } else {
    hypergeometricTail(b.u, b.v, b.w, xMax, tail.data());
  }
  double best = 0.0;
  double missAll = 1.0;  // (1 - lb)^x
  for (int x = 1; x <= xMax; ++x) {
    missAll *= 1.0 - lb;
    best = std::max(best, tail[x - 1] * (1.0 - missAll));
  }
  return {std::clamp(best, 0.0, 1.0), tail[0]};
}

double cellIntersectionBound(int depthA, int depthB, int maxDepthA, int maxDepthB) {
  const int den = maxDepthA + maxDepthB;
  if (den <= 0) return 0.0;
  return std::clamp(static_cast<double>(depthA + depthB) / den, 0.0, 1.0);
}

}  // namespace adb
