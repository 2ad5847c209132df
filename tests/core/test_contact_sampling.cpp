// What contact generation asks of a query beyond a yes/no: sampled hits per contact region
// (QuerySettings::hitsPerRegion), running a query in steps (Traversal), and
// the model's estimates of the pairs an exact query leaves when it is cut.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <vector>

#include "adb/support/mesh_generators.h"
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

// A query run in steps of 37 node pairs until it completes does exactly the work of one
// uninterrupted (budgeted) query: same node pairs in all, same hits in the same order.
TEST_F(OverlappingTori, ATraversalRunInStepsEqualsAnUninterruptedQuery) {
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

      Traversal parts(tree, p.a, tree, p.b, s);
      std::uint64_t nodePairs = 0;
      int steps = 0;
      while (!parts.done() && steps < 100000) {
        parts.step(StepBudget{37});
        EXPECT_LE(parts.lastStep().nodePairs, 37u);
        nodePairs += parts.lastStep().nodePairs;
        ++steps;
      }
      const QueryResult& r = parts.result();
      ASSERT_EQ(r.stop, StopReason::Completed);
      EXPECT_EQ(r.collides, whole.collides);
      EXPECT_EQ(nodePairs, whole.nodePairs);
      EXPECT_EQ(r.nodePairs, whole.nodePairs);  // the result counts every step
      ASSERT_EQ(parts.witnesses().size(), wholeHits.size());
      for (std::size_t i = 0; i < wholeHits.size(); ++i) {
        EXPECT_EQ(parts.witnesses()[i].triangleA, wholeHits[i].triangleA);
        EXPECT_EQ(parts.witnesses()[i].triangleB, wholeHits[i].triangleB);
      }
      if (whole.nodePairs > 37) {
        EXPECT_GT(steps, 1);
      }
    }
  }
}

// The witnesses of a sampled exact query, in the order found.
std::vector<TrianglePair> sampledHits(const AdbTree& tree, const PosePair& p,
                                      ExactDescent descent, std::uint64_t firstStep) {
  QuerySettings s = allHits();
  s.hitsPerRegion = 2;
  s.regionDepth = 6;
  s.descent = descent;
  Traversal t(tree, p.a, tree, p.b, s);
  t.step(StepBudget{firstStep});
  while (!t.done()) t.step();
  std::vector<TrianglePair> out;
  for (const Witness& w : t.witnesses()) out.emplace_back(w.triangleA, w.triangleB);
  return out;
}

TEST_F(OverlappingTori, TheDescentOrderIsASettingNotASideEffectOfTheBudget) {
  constexpr std::uint64_t kUnlimited = std::numeric_limits<std::uint64_t>::max();
  int orderMatters = 0;
  for (const PosePair& p : poses) {
    const std::vector<TrianglePair> treeOrder = sampledHits(tree, p, ExactDescent::TreeOrder,
                                                            kUnlimited);
    // TreeOrder: a budget (here one that cuts the first step) changes nothing.
    EXPECT_EQ(sampledHits(tree, p, ExactDescent::TreeOrder, 40), treeOrder);
    // Auto: the trees' order without a budget, deepest first with one.
    EXPECT_EQ(sampledHits(tree, p, ExactDescent::Auto, kUnlimited), treeOrder);
    const std::vector<TrianglePair> deepest =
        sampledHits(tree, p, ExactDescent::DeepestFirst, kUnlimited);
    EXPECT_EQ(sampledHits(tree, p, ExactDescent::Auto, 40), deepest);
    orderMatters += deepest != treeOrder ? 1 : 0;
  }
  // Sampling keeps the first hits of each region: the order must show in them somewhere,
  // or this test could not tell the settings apart.
  EXPECT_GT(orderMatters, 0);
}

TEST_F(OverlappingTori, StoppingWhenTheWitnessesAreFullKeepsTheSameWitnesses) {
  int stoppedEarly = 0;
  for (const PosePair& p : poses) {
    QuerySettings s = allHits();
    s.hitsPerRegion = 4;
    s.maxWitnesses = 16;
    const QueryResult whole = collide(tree, p.a, tree, p.b, s, scratch);
    const std::vector<Witness> wholeHits = scratch.witnesses();
    s.stopWhenWitnessesFull = true;
    const QueryResult early = collide(tree, p.a, tree, p.b, s, scratch);
    EXPECT_EQ(early.collides, whole.collides);
    ASSERT_EQ(scratch.witnesses().size(), wholeHits.size());
    for (std::size_t i = 0; i < wholeHits.size(); ++i) {
      EXPECT_EQ(scratch.witnesses()[i].triangleA, wholeHits[i].triangleA);
      EXPECT_EQ(scratch.witnesses()[i].triangleB, wholeHits[i].triangleB);
    }
    if (wholeHits.size() < s.maxWitnesses) {
      // Never full: the whole query, to the last node pair.
      EXPECT_EQ(early.stop, StopReason::Completed);
      EXPECT_EQ(early.nodePairs, whole.nodePairs);
    } else {
      EXPECT_EQ(early.stop, StopReason::WitnessesFull);
      EXPECT_EQ(early.confidence, 1.0);
      EXPECT_EQ(early.witnessesDropped, 0u);
      EXPECT_LE(early.nodePairs, whole.nodePairs);
      stoppedEarly += early.nodePairs < whole.nodePairs ? 1 : 0;
    }
  }
  EXPECT_GT(stoppedEarly, 0) << "no pose filled the witnesses early: the test shows nothing";
}

// Found by fuzzing: steps of 1 to 3 node pairs (less than one expansion) used to make no
// progress, so a caller looping until done livelocked. Every step with a non-zero budget
// now takes at least one pair off the frontier, and every pair on it was counted once when
// it was tested, so the steps are at most the uninterrupted query's node pairs (+1 for the
// roots). Both modes end with the uninterrupted query's answer and work.
TEST_F(OverlappingTori, StepsSmallerThanOneExpansionStillProgress) {
  const PosePair& p = poses.front();
  for (QueryMode mode : {QueryMode::Exact, QueryMode::Adb}) {
    QuerySettings s = allHits();
    s.mode = mode;
    s.pruneImprobable = false;  // ADB then completes with the exact answer
    s.budgetNodePairs = std::numeric_limits<std::uint64_t>::max() - 1;
    const QueryResult whole = collide(tree, p.a, tree, p.b, s, scratch);
    for (std::uint64_t budget : {1u, 2u, 3u}) {
      Traversal t(tree, p.a, tree, p.b, s);
      int steps = 0;
      const std::uint64_t bound = whole.nodePairs + 1;
      while (!t.done() && steps <= static_cast<int>(bound)) {
        t.step(StepBudget{budget});
        ++steps;
      }
      ASSERT_TRUE(t.done()) << "no end after " << steps << " steps; mode "
                            << static_cast<int>(mode) << ", budget " << budget;
      EXPECT_LE(static_cast<std::uint64_t>(steps), bound);
      EXPECT_EQ(t.result().collides, whole.collides);
      EXPECT_EQ(t.result().nodePairs, whole.nodePairs) << "budget " << budget;
    }
  }
}

// A zero budget is the one step that may do nothing: it says so (WorkBudget) and changes
// nothing; a finished traversal's step returns the same result; reset() starts afresh, also
// on other trees.
TEST_F(OverlappingTori, ZeroStepsDoNothingAndResetStartsAfresh) {
  const PosePair& p = poses.front();
  QuerySettings s = allHits();
  Traversal t(tree, p.a, tree, p.b, s);
  t.step(StepBudget{5});
  const std::uint64_t after = t.result().nodePairs;
  ASSERT_FALSE(t.done());
  t.step(StepBudget{0});
  EXPECT_EQ(t.result().nodePairs, after);
  EXPECT_EQ(t.result().stop, StopReason::WorkBudget);
  t.step();
  ASSERT_TRUE(t.done());
  const QueryResult final = t.result();
  t.step();
  EXPECT_EQ(t.result().nodePairs, final.nodePairs);
  EXPECT_EQ(t.lastStep().nodePairs, 0u);

  const TriangleMesh small = gen::makeTorus(1.0, 0.35, 12, 6);
  const AdbTree other(small);
  t.reset(other, p.a, other, p.b, s);
  t.step();
  QueryScratch clean;
  const QueryResult expected = collide(other, p.a, other, p.b, s, clean);
  EXPECT_EQ(t.result().nodePairs, expected.nodePairs);
  EXPECT_EQ(t.result().witnessCount, expected.witnessCount);
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
    // The evidence the open pairs give (collision_estimate.h), rebuilt here from them; what
    // they do not carry (the blind pairs' keys, the fills, the work done) from a Traversal
    // stepped the same way.
    Traversal same(tree, p.a, tree, p.b, s);
    same.step(StepBudget{s.budgetNodePairs});
    Evidence evidence = same.evidence();
    const Evidence fromTraversal = evidence;
    evidence.frontierDoubt = evidence.bestOpen = evidence.expectedCells = 0.0;
    double miss = 1.0;
    for (const OpenPair& o : scratch.openPairs()) {
      EXPECT_TRUE(o.p >= 0.0f && o.p <= 1.0f) << o.p;
      EXPECT_TRUE(o.upper >= 0.0f && o.upper <= 1.0f) << o.upper;
      EXPECT_TRUE(o.fill >= 0.0f && o.fill <= 1.0f) << o.fill;
      evidence.frontierDoubt += o.upper;
      evidence.bestOpen = std::max(evidence.bestOpen, static_cast<double>(o.p));
      evidence.expectedCells += o.expected;
      miss *= 1.0 - static_cast<double>(o.p);
    }
    evidence.frontierUnion = 1.0 - miss;
    evidence.openPairs = static_cast<std::uint32_t>(scratch.openPairs().size());
    EXPECT_NEAR(evidence.frontierDoubt, fromTraversal.frontierDoubt, 1e-6);
    EXPECT_NEAR(evidence.frontierUnion, fromTraversal.frontierUnion, 1e-9);
    EXPECT_EQ(evidence.openPairs, fromTraversal.openPairs);
    withOpen += scratch.openPairs().empty() ? 0 : 1;
    EXPECT_TRUE(r.confidence >= 0.0 && r.confidence <= 1.0);
    if (r.collides) {
      EXPECT_EQ(r.confidence, 1.0);
    } else {
      // Exact mode cut says "no" with the estimate's 1 - P.
      EXPECT_NEAR(r.confidence, 1.0 - collisionProbability(evidence), 1e-9);
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
