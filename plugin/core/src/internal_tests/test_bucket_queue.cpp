// The ADB queue (bucket_queue.h) and its key (priority_table.h): the highest bucket first,
// the newest entry first inside a bucket, removal keeping the order, and a key that grows
// with both the expected cells and the depth term, as Eq. 3 does.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "adb/core/probability.h"
#include "bucket_queue.h"
#include "priority_table.h"
#include "test_support.h"

namespace adb {
namespace {

struct Item {
  int id;
};
using Queue = detail::BucketQueue<Item, detail::kPriorityBuckets>;

TEST(BucketQueue, PopsTheHighestBucketFirstAndTheNewestWithinIt) {
  Queue q;
  q.push({1}, 5);
  q.push({2}, 100);
  q.push({3}, 5);
  q.push({4}, 127);
  q.push({5}, 0);
  q.push({6}, 100);
  std::vector<int> order;
  int bucket = -1;
  while (!q.empty()) order.push_back(q.pop(bucket).id);
  EXPECT_EQ(order, (std::vector<int>{4, 6, 2, 3, 1, 5}));
  EXPECT_EQ(q.size(), 0u);
}

// Against a reference: a stable sort by bucket, newest first, on random pushes and pops.
TEST(BucketQueue, MatchesASortedReferenceOnRandomPushesAndPops) {
  std::mt19937_64 rng(test::kSeed);
  Queue q;
  std::vector<std::pair<int, int>> reference;  // (bucket, id) in push order
  int next = 0;
  for (int op = 0; op < 20000; ++op) {
    if (reference.empty() || rng() % 3 != 0) {
      const int bucket = static_cast<int>(rng() % detail::kPriorityBuckets);
      q.push({next}, bucket);
      reference.emplace_back(bucket, next++);
      continue;
    }
    std::size_t best = 0;  // the highest bucket, latest pushed among equals
    for (std::size_t k = 0; k < reference.size(); ++k) {
      if (reference[k].first >= reference[best].first) best = k;
    }
    int bucket = -1;
    const Item got = q.pop(bucket);
    ASSERT_EQ(got.id, reference[best].second) << "operation " << op;
    ASSERT_EQ(bucket, reference[best].first);
    reference.erase(reference.begin() + static_cast<std::ptrdiff_t>(best));
    ASSERT_EQ(q.size(), reference.size());
  }
}

TEST(BucketQueue, RemovingKeepsTheOthersInOrder) {
  Queue q;
  for (int i = 0; i < 10; ++i) q.push({i}, i % 2 == 0 ? 7 : 64);
  EXPECT_EQ(q.removeIf([](const Item& it) { return it.id % 3 == 0; }), 4u);
  std::vector<int> order;
  int bucket = -1;
  while (!q.empty()) order.push_back(q.pop(bucket).id);
  EXPECT_EQ(order, (std::vector<int>{7, 5, 1, 8, 4, 2}));
}

TEST(PriorityTable, GrowsWithTheExpectedCellsAndTheDepthTerm) {
  const detail::PriorityTable& t = detail::priorityTable();
  for (int row = 0; row < detail::kPriorityRows; ++row) {
    for (int column = 0; column < detail::kPriorityColumns; ++column) {
      if (row > 0) {
        EXPECT_GE(t.bucket[row][column], t.bucket[row - 1][column]);
      }
      if (column > 0) {
        EXPECT_GE(t.bucket[row][column], t.bucket[row][column - 1]);
      }
    }
  }
  // Deep, many expected cells: near 1; shallow and sparse: near 0.
  EXPECT_GE(detail::priorityBucket(t, 64.0f, detail::priorityColumn(0.9)),
            detail::kPriorityBuckets - 2);
  EXPECT_LE(detail::priorityBucket(t, 1e-6f, detail::priorityColumn(0.1)), 5);
}

// The key approximates Eq. 3 where the cells are sparse: within one bucket's width (2^(1/8),
// 9 %) or two, over typical pairs below the top of the trees.
TEST(PriorityTable, ApproximatesEq3ForSparseCells) {
  const detail::PriorityTable& t = detail::priorityTable();
  int within = 0, total = 0;
  for (int s : {64, 256, 1000, 4096}) {
    for (int sa = 1; sa <= s / 8; sa += 1 + sa / 4) {
      for (int sb = 1; sb <= s / 8; sb += 1 + sb / 4) {
        for (double lb : {0.2, 0.5, 0.8}) {
          const double eq3 = collisionLowerBound(s, sa, sb, lb);
          const double expected = static_cast<double>(sa) * sb / s;
          const int key = detail::priorityBucket(t, static_cast<float>(expected),
                                                 detail::priorityColumn(lb));
          ++total;
          if (std::abs(key - detail::bucketOfProbability(eq3)) <= 2) ++within;
        }
      }
    }
  }
  EXPECT_GT(within, total * 9 / 10) << within << " of " << total;
}

}  // namespace
}  // namespace adb
