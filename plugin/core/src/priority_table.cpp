#include "priority_table.h"

#include <algorithm>
#include <cmath>

#include "adb/core/probability.h"

namespace adb::detail {
namespace {

// Pr[Y >= x] for x = 1..kMaxCollisionCells, Y ~ Poisson(mean): the terms follow from
// e^-mean by their ratio; where e^-mean underflows every tail up to x = 10 is 1 to rounding.
void poissonTails(double mean, double tails[kMaxCollisionCells]) {
  double term = std::exp(-mean);  // Pr[Y = 0]
  double below = 0.0;             // Pr[Y < x]
  for (int x = 1; x <= kMaxCollisionCells; ++x) {
    below += term;
    term *= mean / x;
    tails[x - 1] = std::clamp(1.0 - below, 0.0, 1.0);
  }
}

// Eq. 3 with the hypergeometric tail replaced by the Poisson tail of the same mean.
double poissonEq3(const double tails[kMaxCollisionCells], double lb) {
  double missAll = 1.0;  // (1 - lb)^x
  double best = 0.0;
  for (int x = 1; x <= kMaxCollisionCells; ++x) {
    missAll *= 1.0 - lb;
    best = std::max(best, tails[x - 1] * (1.0 - missAll));
  }
  return best;
}

PriorityTable build() {
  PriorityTable t{};
  for (int row = 0; row < kPriorityRows; ++row) {
    const int exponent = row / 4 + kPriorityLowestExponent;
    double tails[kMaxCollisionCells];  // one row's tails serve its 64 columns
    poissonTails(std::ldexp(1.0 + ((row % 4) + 0.5) / 4.0, exponent), tails);
    for (int column = 0; column < kPriorityColumns; ++column) {
      const double lb = (column + 0.5) / kPriorityColumns;
      const int bucket = bucketOfProbability(poissonEq3(tails, lb));
      t.bucket[row][column] = static_cast<std::uint8_t>(bucket);
    }
  }
  for (int b = 0; b < kPriorityBuckets; ++b) {
    t.probability[b] = std::exp2((b - kPriorityBuckets + 0.5) / 8.0);
    t.logMiss[b] = std::log1p(-t.probability[b]);
  }
  return t;
}

}  // namespace

int bucketOfProbability(double p) {
  if (!(p > 0.0)) return 0;
  const double b = std::floor(8.0 * std::log2(std::min(p, 1.0))) + kPriorityBuckets;
  return static_cast<int>(std::clamp(b, 0.0, kPriorityBuckets - 1.0));
}

const PriorityTable& priorityTable() {
  static const PriorityTable table = build();
  return table;
}

}  // namespace adb::detail
