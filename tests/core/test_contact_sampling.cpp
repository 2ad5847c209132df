// What contact generation asks of a query beyond a yes/no: sampled hits per contact region
// (QuerySettings::hitsPerRegion), resuming a query a budget cut (QuerySettings::resume), and
// the model's estimates of the pairs an exact query leaves when it is cut.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <vector>

#include "adb/core/mesh_generators.h"
#include "adb/core/tree.h"
#include "test_support.h"

namespace adb {
namespace {

using TrianglePair = std::tuple<std::uint32_t, std::uint32_t>;

std::vector<TrianglePair> trianglePairs(const QueryScratch& scratch) {
  std::vector<TrianglePair> out;
  for (const Witness& w : scratch.witnesses()) {
    EXPECT_TRUE(w.isExact());
    out.emplace_back(w.triangleA, w.triangleB);
  }
  std::sort(out.begin(), out.end());
  return out;
}

QuerySettings allHits() {
  QuerySettings s = test::exactSettings();
  s.stopAtFirstHit = false;
  s.maxWitnesses = 1000000;
  return s;
}

// Deeply overlapping tori: hundreds of intersecting triangle pairs spread around the overlap.
struct OverlappingTori : ::testing::Test {
  TriangleMesh mesh = gen::makeTorus(1.0, 0.35, 48, 24);
  AdbTree tree{mesh};
  QueryScratch scratch;
  std::vector<PosePair> poses;

  void SetUp() override {
    std::mt19937_64 rng(test::kSeed);
    for (double dist : {0.2, 0.4, 0.6, 0.9, 1.2, 1.6}) {
      for (int i = 0; i < 4; ++i) poses.push_back(benchmarkPoses(mesh.bounds(), dist, rng));
    }
  }
};

TEST_F(OverlappingTori, SamplingKeepsTheAnswerAndTestsFewerTriangles) {
  std::uint64_t fullTests = 0, sampledTests = 0;
  int collisions = 0, sampledBelowFull = 0;
  for (const PosePair& p : poses) {
    const QueryResult full = collide(tree, p.a, tree, p.b, allHits(), scratch);
    const std::vector<TrianglePair> fullHits = trianglePairs(scratch);
    QuerySettings s = allHits();
    s.hitsPerRegion = 2;
    s.regionDepth = 6;
    const QueryResult sampled = collide(tree, p.a, tree, p.b, s, scratch);
    const std::vector<TrianglePair> sampledHits = trianglePairs(scratch);
    EXPECT_EQ(sampled.collides, full.collides);
    EXPECT_EQ(sampled.stop, StopReason::Completed);
    EXPECT_EQ(sampled.confidence, 1.0);
    // A sample of the real hits, at least one whenever there is one.
    EXPECT_TRUE(std::includes(fullHits.begin(), fullHits.end(), sampledHits.begin(),
                              sampledHits.end()));
    EXPECT_EQ(sampledHits.empty(), fullHits.empty());
    collisions += full.collides ? 1 : 0;
    sampledBelowFull += sampledHits.size() < fullHits.size() ? 1 : 0;
    fullTests += full.triangleTests;
    sampledTests += sampled.triangleTests;
  }
  ASSERT_GT(collisions, 10) << "the poses must overlap for the comparison to mean anything";
  EXPECT_GT(sampledBelowFull, collisions / 2);
  EXPECT_LT(sampledTests * 2, fullTests) << "sampling must save at least half the tests";
}

TEST_F(OverlappingTori, OneRegionHoldsExactlyItsQuota) {
  // regionDepth 0: the roots are the only region, so the sample is the first hitsPerRegion
  // hits (or all of them where there are fewer).
  for (const PosePair& p : poses) {
    collide(tree, p.a, tree, p.b, allHits(), scratch);
    const std::size_t all = scratch.witnesses().size();
    QuerySettings s = allHits();
    s.hitsPerRegion = 3;
    s.regionDepth = 0;
    const QueryResult r = collide(tree, p.a, tree, p.b, s, scratch);
    EXPECT_EQ(r.witnessCount, std::min<std::size_t>(all, 3));
  }
}

TEST_F(OverlappingTori, BestFirstSamplingAgreesWithExactMode) {
  for (const PosePair& p : poses) {
    const QueryResult exact = collide(tree, p.a, tree, p.b, allHits(), scratch);
    QuerySettings s = test::adbSettings(0.99, std::numeric_limits<int>::max());
    s.stopAtFirstHit = false;
    s.pruneImprobable = false;
    s.nodeWitnesses = false;
    s.hitsPerRegion = 2;
    s.regionDepth = 6;
    const QueryResult r = collide(tree, p.a, tree, p.b, s, scratch);
    EXPECT_EQ(r.collides, exact.collides);
    EXPECT_EQ(r.stop, StopReason::Completed);
    EXPECT_TRUE(scratch.openPairs().empty());
  }
}

// A query cut every 37 node pairs and resumed until it completes does exactly the work of
// one uninterrupted (budgeted) query: same node pairs in all, same hits in the same order.
TEST_F(OverlappingTori, ResumedQueryEqualsAnUninterruptedOne) {
  for (bool sampled : {false, true}) {
    for (const PosePair& p : poses) {
      QuerySettings s = allHits();
      if (sampled) {
        s.hitsPerRegion = 2;
        s.regionDepth = 6;
      }
      // A budget it never reaches: a query that may be cut descends deepest overlap first,
      // so the reference must be one too.
      s.budgetNodePairs = std::numeric_limits<std::uint64_t>::max() - 1;
      const QueryResult whole = collide(tree, p.a, tree, p.b, s, scratch);
      ASSERT_EQ(whole.stop, StopReason::Completed);
      const std::vector<Witness> wholeHits = scratch.witnesses();

      QueryScratch parts;
      s.budgetNodePairs = 37;
      QueryResult r = collide(tree, p.a, tree, p.b, s, parts);
      std::uint64_t nodePairs = r.nodePairs;
      int calls = 1;
      s.resume = true;
      while (r.stop == StopReason::WorkBudget && calls < 100000) {
        EXPECT_LE(r.nodePairs, 37u);
        r = collide(tree, p.a, tree, p.b, s, parts);
        nodePairs += r.nodePairs;
        ++calls;
      }
      ASSERT_EQ(r.stop, StopReason::Completed);
      EXPECT_EQ(r.collides, whole.collides);
      EXPECT_EQ(nodePairs, whole.nodePairs);
      ASSERT_EQ(parts.witnesses().size(), wholeHits.size());
      for (std::size_t i = 0; i < wholeHits.size(); ++i) {
        EXPECT_EQ(parts.witnesses()[i].triangleA, wholeHits[i].triangleA);
        EXPECT_EQ(parts.witnesses()[i].triangleB, wholeHits[i].triangleB);
      }
      if (whole.nodePairs > 37) {
        EXPECT_GT(calls, 1);
      }
    }
  }
}

TEST_F(OverlappingTori, ResumeStartsAfreshForOtherTreesOrACompletedQuery) {
  const PosePair& p = poses.front();
  QuerySettings s = allHits();
  const QueryResult whole = collide(tree, p.a, tree, p.b, s, scratch);
  ASSERT_EQ(whole.stop, StopReason::Completed);
  s.resume = true;  // nothing to resume: the same query again
  const QueryResult again = collide(tree, p.a, tree, p.b, s, scratch);
  EXPECT_EQ(again.nodePairs, whole.nodePairs);
  EXPECT_EQ(again.witnessCount, whole.witnessCount);

  // Cut on one pair of trees, resumed on another: a fresh query of the other.
  const TriangleMesh small = gen::makeTorus(1.0, 0.35, 12, 6);
  const AdbTree other(small);
  s.resume = false;
  s.budgetNodePairs = 5;
  ASSERT_EQ(collide(tree, p.a, tree, p.b, s, scratch).stop, StopReason::WorkBudget);
  s.resume = true;
  s.budgetNodePairs = std::numeric_limits<std::uint64_t>::max();
  const QueryResult fresh = collide(other, p.a, other, p.b, s, scratch);
  QueryScratch clean;
  s.resume = false;
  const QueryResult expected = collide(other, p.a, other, p.b, s, clean);
  EXPECT_EQ(fresh.nodePairs, expected.nodePairs);
  EXPECT_EQ(fresh.witnessCount, expected.witnessCount);
}

TEST_F(OverlappingTori, ACutExactQueryEstimatesWhatItLeft) {
  int withOpen = 0;
  for (const PosePair& p : poses) {
    QuerySettings s = allHits();
    s.budgetNodePairs = 40;
    const QueryResult r = collide(tree, p.a, tree, p.b, s, scratch);
    if (r.stop == StopReason::Completed) {
      EXPECT_TRUE(scratch.openPairs().empty());
      continue;
    }
    ASSERT_EQ(r.stop, StopReason::WorkBudget);
    double doubt = 0.0;
    for (const OpenPair& o : scratch.openPairs()) {
      EXPECT_TRUE(o.p >= 0.0f && o.p <= 1.0f) << o.p;
      EXPECT_TRUE(o.upper >= o.p && o.upper <= 1.0f) << o.p << " " << o.upper;
      doubt += o.upper;
    }
    withOpen += scratch.openPairs().empty() ? 0 : 1;
    EXPECT_TRUE(r.confidence >= 0.0 && r.confidence <= 1.0);
    if (r.collides) {
      EXPECT_EQ(r.confidence, 1.0);
    } else {
      EXPECT_NEAR(r.confidence, 1.0 - std::min(1.0, doubt), 1e-6);
    }
  }
  EXPECT_GT(withOpen, 5);
}

TEST(ContactSamplingSettings, NegativeRegionDepthIsRefusedByName) {
  QuerySettings s;
  s.regionDepth = -1;
  try {
    validate(s);
    FAIL() << "a negative regionDepth must be refused";
  } catch (const SettingsError& e) {
    EXPECT_NE(std::string(e.what()).find("regionDepth"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace adb
