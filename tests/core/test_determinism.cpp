// A pinned hash over a fixed set of queries, as Box2D pins its EXPECTED_HASH: the answer, the
// confidence's bits and the node pairs of every query. Any change to what the traversal
// visits, in what order, or to the numbers it reports shows here. A change that is meant
// (a new model, a new fit) updates the hash in the same commit, saying why.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

#include "adb/core/benchmark_poses.h"
#include "adb/core/mesh_generators.h"
#include "adb/core/query.h"
#include "adb/core/tree.h"
#include "test_support.h"

namespace adb {
namespace {

// FNV-1a, 64 bits.
struct Hash {
  std::uint64_t h = 1469598103934665603ull;
  void add(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  }
  template <class T>
  void add(const T& v) {
    add(&v, sizeof v);
  }
};

std::uint64_t queryHash() {
  const TriangleMesh mesh = gen::makeModel("knot", 5000);
  const AdbTree tree(mesh);
  QueryScratch scratch;
  std::mt19937_64 rng(test::kSeed);
  Hash hash;
  for (int i = 0; i < 60; ++i) {
    const PosePair p = benchmarkPoses(mesh.bounds(), 0.4 + 0.027 * i, rng);
    // Work budgets only: a time budget would make the hash depend on the machine.
    for (std::uint64_t budget : {std::uint64_t{7}, std::uint64_t{60}, std::uint64_t{500},
                                 std::numeric_limits<std::uint64_t>::max()}) {
      for (QuerySettings s : {test::adbSettings(), test::adbSettings(0.9, 1), test::exactSettings()}) {
        s.budgetNodePairs = budget;
        const QueryResult r = collide(tree, p.a, tree, p.b, s, scratch);
        hash.add(r.collides);
        std::uint64_t bits = 0;
        std::memcpy(&bits, &r.confidence, sizeof bits);
        hash.add(bits);
        hash.add(r.nodePairs);
        hash.add(r.triangleTests);
      }
    }
  }
  return hash.h;
}

TEST(Determinism, PinnedHashOfAFixedQuerySet) {
  // Set by the commit that last changed what queries do; see the file comment.
  constexpr std::uint64_t kExpectedHash = 0x7637e15a0895a086ull;
  EXPECT_EQ(queryHash(), kExpectedHash) << std::hex << "hash 0x" << queryHash();
}

TEST(Determinism, TheSameQueriesGiveTheSameHashTwice) {
  EXPECT_EQ(queryHash(), queryHash());
}

}  // namespace
}  // namespace adb
