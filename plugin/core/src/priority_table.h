// Internal: the ADB queue's cheap key — a table that approximates Eq. 3 by a pair's expected
// collision cells and its depth term, already quantised into the queue's buckets.
//
// Eq. 3 (max over x of Pr[X >= x] (1 - (1 - LB)^x)) costs a hundred operations or more per
// pair, and the traversal evaluated it for every overlapping pair only to order them. The
// order needs far less: Pr[X >= x] is close to a Poisson tail of mean E[X] = s_A s_B / s when
// the cells are sparse, which they are below the top of the trees, and LB is a depth ratio
// that takes a few dozen values. So the key is read from a table indexed by E[X] (its float
// exponent and two mantissa bits: rows 19 % apart) and LB (64 columns), holding the Poisson
// form of Eq. 3 at the middle of each cell, already turned into a bucket of the queue
// (kPriorityBuckets, eight per halving of the probability). Box overlap alone ordered badly
// (the study's box-first traversal); the depth term is what lets a deep pair with few
// expected cells go before a shallow one with many. Acceptance still runs Eq. 3 itself where
// its pre-test (collisionLowerBoundCouldExceed) allows, so what is accepted does not change.
#pragma once

#include <cstdint>
#include <cstring>

namespace adb::detail {

/// Buckets of the ADB queue: bucket b holds keys in [2^((b - 128) / 8), 2^((b - 127) / 8)),
/// bucket 0 also everything smaller, bucket 127 also 1.
inline constexpr int kPriorityBuckets = 128;
inline constexpr int kPriorityColumns = 64;
inline constexpr int kPriorityLowestExponent = -24;  // E[X] below 2^-24: the first rows' key
inline constexpr int kPriorityHighestExponent = 10;  // E[X] from 2^11 up: the last row's
inline constexpr int kPriorityRows =
    (kPriorityHighestExponent - kPriorityLowestExponent + 1) * 4;

struct PriorityTable {
  std::uint8_t bucket[kPriorityRows][kPriorityColumns];
  double probability[kPriorityBuckets];  // each bucket's key: the middle of its range
  double logMiss[kPriorityBuckets];      // log(1 - probability): the frontier's union
};

/// Built once (thread-safe static initialisation), 9 KiB.
const PriorityTable& priorityTable();

/// The column of a depth term LB in [0, 1].
inline int priorityColumn(double lb) {
  const int c = static_cast<int>(lb * kPriorityColumns);
  return c < 0 ? 0 : (c >= kPriorityColumns ? kPriorityColumns - 1 : c);
}

/// The row of an expected cell count: its exponent and first two mantissa bits as a float.
inline int priorityRow(float expected) {
  std::uint32_t bits = 0;
  std::memcpy(&bits, &expected, sizeof bits);
  const int exponent = static_cast<int>((bits >> 23) & 0xFFu) - 127;
  if (exponent < kPriorityLowestExponent) return 0;
  if (exponent > kPriorityHighestExponent) return kPriorityRows - 1;
  return (exponent - kPriorityLowestExponent) * 4 + static_cast<int>((bits >> 21) & 3u);
}

/// The bucket of a pair with E[X] = expected at depth-term column `column`.
inline int priorityBucket(const PriorityTable& t, float expected, int column) {
  return t.bucket[priorityRow(expected)][column];
}

/// The bucket of a key value in [0, 1].
int bucketOfProbability(double p);

}  // namespace adb::detail
