// Balls-into-bins probabilities (paper §3.6.1-3.6.3), exact in double for u <= kMaxBins.
#include "adb/core/probability.h"

#include "probability_tables.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
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

namespace {

// The traversal evaluates Eq. 3 for every overlapping node pair, so it avoids exp, log and
// division: n! is tabulated as mantissa * 2^exponent (no overflow up to kMaxBins!), and the
// term ratios multiply by tabulated reciprocals. Both tables are built once (thread-safe
// static initialisation); a query reads their first few thousand entries.
struct FactorialTables {
  // n! = mantissa * 2^exponent, mantissa in [1, 2): side by side, one cache line per lookup.
  struct Factorial {
    double mantissa;
    int exponent;
  };
  std::vector<Factorial> factorial;
  std::vector<double> reciprocal;  // 1 / n (0 for n = 0, never read)
  FactorialTables() : factorial(kMaxBins + 1), reciprocal(kMaxBins + 1) {
    // Accumulated in long double (a 64-bit mantissa on x86): 32768 roundings stay far
    // below double precision.
    long double m = 1.0L;
    int e = 0;
    for (int n = 0; n <= kMaxBins; ++n) {
      if (n > 0) {
        int shift = 0;
        m = std::frexp(m * n, &shift) * 2.0L;  // back into [1, 2)
        e += shift - 1;
        reciprocal[n] = 1.0 / n;
      }
      factorial[n] = {static_cast<double>(m), e};
    }
  }
};

const FactorialTables& factorials() {
  static const FactorialTables tables;
  return tables;
}

// Pr[X = t] = v! (u-v)! w! (u-w)! / (u! t! (v-t)! (w-t)! (u-v-w+t)!), for t0 <= t <= min(v, w).
// Underflows to 0 where it is below 2^-1022: the tails it feeds are then 1 to rounding.
double pointProbability(const FactorialTables& f, int u, int v, int w, int t) {
  const int num[4] = {v, u - v, w, u - w};
  const int den[5] = {u, t, v - t, w - t, u - v - w + t};
  double m = 1.0;
  int e = 0;
  for (int n : num) {
    m *= f.factorial[n].mantissa;
    e += f.factorial[n].exponent;
  }
  double d = 1.0;
  for (int n : den) {
    d *= f.factorial[n].mantissa;
    e -= f.factorial[n].exponent;
  }
  // m / d is in [1/32, 16) and the probability is <= 1, so e <= 5. Below the normal range the
  // term is under 2^-1000: 0 for the tails it feeds. 2^e from its bits: ldexp is a library
  // call, and this runs for every node pair.
  if (e < -1000) return 0.0;
  const std::uint64_t bits = static_cast<std::uint64_t>(e + 1023) << 52;
  double scale = 0.0;
  std::memcpy(&scale, &bits, sizeof scale);
  return m / d * scale;
}

}  // namespace

namespace detail {

void prepareProbabilityTables() {
  logFactorials();
  factorials();
}

}  // namespace detail

CollisionEstimate estimateCollision(int s, int sA, int sB, double lb) {
  const Bins b = clampBins(s, sA, sB);
  const int xMax = std::min({b.v, b.w, kMaxCollisionCells});
  if (xMax <= 0) return {};
  lb = std::isnan(lb) ? 0.0 : std::clamp(lb, 0.0, 1.0);
  const double miss = 1.0 - lb;
  // At least t0 = v + w - u bins get both colours: Pr[X >= x] = 1 for x <= t0, and with
  // (1 - (1 - lb)^x) growing in x the best of those is at x = min(t0, xMax).
  const int t0 = std::max(0, b.v + b.w - b.u);
  double missAll = 1.0;  // (1 - lb)^x
  for (int x = 1; x <= std::min(t0, xMax); ++x) missAll *= miss;
  double best = 1.0 - missAll;
  if (t0 >= xMax) return {std::clamp(best, 0.0, 1.0), 1.0};
  const FactorialTables& f = factorials();
  double p = pointProbability(f, b.u, b.v, b.w, t0);  // Pr[X = t0]
  const double upper = t0 == 0 ? std::clamp(1.0 - p, 0.0, 1.0) : 1.0;
  double below = 0.0;  // Pr[X <= t]
  for (int t = t0; t < xMax; ++t) {
    below += p;
    const double tail = 1.0 - below;  // Pr[X >= t + 1]
    // Tails only fall as x grows and (1 - (1 - lb)^x) <= 1: no later x can beat `best`.
    if (tail <= best) break;
    missAll *= miss;
    best = std::max(best, tail * (1.0 - missAll));
    // Pr[X = t+1] / Pr[X = t] = (v - t)(w - t) / ((t + 1)(u - v - w + t + 1)); the second
    // factor of the denominator is >= 1 because t >= t0.
    p *= static_cast<double>(b.v - t) * (b.w - t) * f.reciprocal[t + 1] *
         f.reciprocal[b.u - b.v - b.w + t + 1];
  }
  return {std::clamp(best, 0.0, 1.0), upper};
}

int smallestPassingCells(double lb, double threshold) {
  lb = std::isnan(lb) ? 0.0 : std::clamp(lb, 0.0, 1.0);
  const double miss = 1.0 - lb;
  // (1 - lb)^x multiplied up as Eq. 3 does: every term of Eq. 3 is at most its depth term (its
  // tail is at most 1), bit for bit.
  double missAll = 1.0;
  for (int x = 1; x <= kMaxCollisionCells; ++x) {
    missAll *= miss;
    if (1.0 - missAll > threshold) return x;
  }
  return kMaxCollisionCells + 1;
}

bool collisionTailCouldExceed(int s, int sA, int sB, int x, double threshold) {
  // Rounding of Eq. 3's tail (a sum of at most ten terms, each exact to a few ulps) is below
  // 1e-14; the margin keeps the bound on the safe side of it.
  constexpr double kMargin = 1e-9;
  const Bins b = clampBins(s, sA, sB);
  if (x > std::min({b.v, b.w, kMaxCollisionCells})) return false;
  // Below t0 = v + w - u the tail is 1: Eq. 3 is at least this x's depth term.
  const int t0 = std::max(0, b.v + b.w - b.u);
  if (x <= t0) return true;
  // Tails fall as x grows: Eq. 3 > threshold needs Pr[X >= x] > threshold at this x.
  const double u = b.u, v = b.v, w = b.w;
  const double mu = v * w / u;
  if (!(x > mu)) return true;
  double tail = mu / x;  // Markov
  if (b.u > 1) {
    const double variance = v * w * (u - v) * (u - w) / (u * u * (u - 1.0));
    const double k = x - mu;
    tail = std::min(tail, variance / (variance + k * k));  // Cantelli
  }
  return tail + kMargin > threshold;
}

bool collisionLowerBoundCouldExceed(int s, int sA, int sB, double lb, double threshold) {
  return collisionTailCouldExceed(s, sA, sB, smallestPassingCells(lb, threshold), threshold);
}

double cellIntersectionBound(int depthA, int depthB, int maxDepthA, int maxDepthB) {
  const int den = maxDepthA + maxDepthB;
  if (den <= 0) return 0.0;
  return std::clamp(static_cast<double>(depthA + depthB) / den, 0.0, 1.0);
}

}  // namespace adb
