#include "priority_table.h"

#include <algorithm>
#include <cmath>

#include "adb/core/probability.h"

namespace adb::detail {
namespace {

// Eq. 3 with the hypergeometric tail replaced by the Poisson tail of the same mean:
// max over x of Pr[Y >= x] (1 - (1 - lb)^x), Y ~ Poisson(mean). The terms follow from
// e^-mean by their ratio; where e^-mean underflows every tail up to x = 10 is 1 to rounding.
double poissonEq3(double mean, double lb) {
  double term = std::exp(-mean);  // Pr[Y = 0]
  double below = 0.0;             // Pr[Y < x]
  double missAll = 1.0;           // (1 - lb)^x
  double best = 0.0;
  for (int x = 1; x <= kMaxCollisionCells; ++x) {
    below += term;
    term *= mean / x;
    missAll *= 1.0 - lb;
    best = std::max(best, std::clamp(1.0 - below, 0.0, 1.0) * (1.0 - missAll));
  }
  return best;
}

PriorityTable build() {
  PriorityTable t{};
  for (int row = 0; row < kPriorityRows; ++row) {
    const int exponent = row / 4 + kPriorityLowestExponent;
    const double mean = std::ldexp(1.0 + ((row % 4) + 0.5) / 4.0, exponent);
    for (int column = 0; column < kPriorityColumns; ++column) {
      const double lb = (column + 0.5) / kPriorityColumns;
      t.bucket[row][column] = static_cast<std::uint8_t>(bucketOfProbability(poissonEq3(mean, lb)));
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
