// Exact mode against the brute-force oracle (all triangle pairs) on random benchmark poses:
// zero disagreements; plus witness collection and budgets in exact mode.
#include <gtest/gtest.h>

#include "adb/support/mesh_generators.h"
#include "adb/core/tree.h"
#include "test_support.h"

namespace adb {
namespace {

struct Disagreements {
  int queries = 0, collisions = 0, wrong = 0;
};

Disagreements compareWithBruteForce(const TriangleMesh& mesh, int posesPerDistance,
                                    const QuerySettings& settings = test::exactSettings()) {
  AdbTree tree(mesh);
  QueryScratch scratch;
  std::mt19937_64 rng(test::kSeed);
  Disagreements d;
  for (double dist = 0.2; dist <= 2.2; dist += 0.1) {
    for (int i = 0; i < posesPerDistance; ++i) {
      const PosePair p = benchmarkPoses(mesh.bounds(), dist, rng);
      const QueryResult r = collide(tree, p.a, tree, p.b, settings, scratch);
      const bool truth = test::bruteForceCollide(mesh, p.a, mesh, p.b);
      ++d.queries;
      d.collisions += truth ? 1 : 0;
      if (r.collides != truth) ++d.wrong;
      EXPECT_EQ(r.confidence, 1.0);
      EXPECT_TRUE(r.stop == StopReason::Completed || r.stop == StopReason::ExactHit);
    }
  }
  return d;
}

TEST(ExactMode, AgreesWithBruteForceOnTorus) {
  const auto d = compareWithBruteForce(gen::makeTorus(1.0, 0.35, 20, 10), 12);
  EXPECT_EQ(d.wrong, 0);
  // The poses must exercise both answers, or the comparison proves little.
  EXPECT_GT(d.collisions, d.queries / 5);
  EXPECT_LT(d.collisions, d.queries * 4 / 5);
}

TEST(ExactMode, AgreesWithBruteForceOnGear) {
  const auto d = compareWithBruteForce(gen::makeGear(12, 1.0, 0.8, 0.3, 0.3, 4), 10);
  EXPECT_EQ(d.wrong, 0);
  EXPECT_GT(d.collisions, d.queries / 5);
}

TEST(ExactMode, AgreesWithBruteForceOnTorusKnot) {
  const auto d = compareWithBruteForce(gen::makeTorusKnot(2, 3, 1.0, 0.25, 48, 6), 10);
  EXPECT_EQ(d.wrong, 0);
  EXPECT_GT(d.collisions, d.queries / 5);
}

// Slivers: a cylinder of long thin side triangles (51:1) and fan caps, whose leaves' boxes
// are mostly empty: the occupied cells (node_occupancy.h) part pairs the boxes cannot, and
// must never part a pair whose triangles meet.
TriangleMesh sliverCylinder() { return gen::makeCylinder(0.3, 2.0, 48, 1, 1); }

TEST(ExactMode, AgreesWithBruteForceOnSlivers) {
  const auto d = compareWithBruteForce(sliverCylinder(), 12);
  EXPECT_EQ(d.wrong, 0);
  EXPECT_GT(d.collisions, d.queries / 5);
  EXPECT_LT(d.collisions, d.queries * 4 / 5);
}

TEST(ExactMode, CollectsEveryIntersectingPairOfSlivers) {
  const TriangleMesh mesh = sliverCylinder();
  AdbTree tree(mesh);
  QueryScratch scratch;
  std::mt19937_64 rng(test::kSeed);
  int collided = 0;
  for (int i = 0; i < 60; ++i) {
    const PosePair p = benchmarkPoses(mesh.bounds(), 0.3 + 0.02 * i, rng);
    const QueryResult r = collide(tree, p.a, tree, p.b, test::collectEverySettings(), scratch);
    const std::size_t expected = test::bruteForceIntersectingPairs(mesh, p.a, mesh, p.b);
    EXPECT_EQ(r.witnessCount, expected) << "pose " << i;
    collided += expected > 0 ? 1 : 0;
  }
  EXPECT_GT(collided, 10);
  EXPECT_LT(collided, 55);
}

QuerySettings mostCellsFirst() {
  QuerySettings s = test::exactSettings();
  s.descent = ExactDescent::MostCellsFirst;
  return s;
}

TEST(ExactMode, MostCellsFirstAgreesWithBruteForce) {
  const auto d = compareWithBruteForce(gen::makeTorusKnot(2, 3, 1.0, 0.25, 48, 6), 10,
                                       mostCellsFirst());
  EXPECT_EQ(d.wrong, 0);
  EXPECT_GT(d.collisions, d.queries / 5);
}

// Most expected cells first reaches the first hit of colliding poses with fewer node pairs
// than the trees' order (measured: 21 to 34 % fewer on the generated models at 20k).
TEST(ExactMode, MostCellsFirstFindsTheFirstHitWithFewerNodePairs) {
  const TriangleMesh mesh = gen::makeModel("knot", 5000);
  const AdbTree tree(mesh);
  QueryScratch scratch;
  QuerySettings treeOrder = test::exactSettings();
  treeOrder.descent = ExactDescent::TreeOrder;
  std::mt19937_64 rng(test::kSeed);
  std::uint64_t pairsTree = 0, pairsCells = 0;
  int colliding = 0;
  for (int i = 0; i < 200; ++i) {
    const PosePair p = benchmarkPoses(mesh.bounds(), 0.4 + 0.008 * i, rng);
    const QueryResult t = collide(tree, p.a, tree, p.b, treeOrder, scratch);
    const QueryResult c = collide(tree, p.a, tree, p.b, mostCellsFirst(), scratch);
    ASSERT_EQ(t.collides, c.collides) << "pose " << i;
    if (!t.collides) continue;
    ++colliding;
    pairsTree += t.nodePairs;
    pairsCells += c.nodePairs;
  }
  EXPECT_GT(colliding, 50);
  EXPECT_LT(static_cast<double>(pairsCells), 0.9 * static_cast<double>(pairsTree));
}

TEST(ExactMode, CollectsEveryIntersectingTrianglePair) {
  const TriangleMesh mesh = gen::makeTorus(1.0, 0.35, 16, 8);
  AdbTree tree(mesh);
  QueryScratch scratch;
  QuerySettings s = test::collectEverySettings();
  std::mt19937_64 rng(test::kSeed);
  const PosePair p = benchmarkPoses(mesh.bounds(), 0.5, rng);
  const QueryResult r = collide(tree, p.a, tree, p.b, s, scratch);
  const std::size_t expected = test::bruteForceIntersectingPairs(mesh, p.a, mesh, p.b);
  ASSERT_GT(expected, 0u);
  EXPECT_EQ(r.witnessCount, expected);
  EXPECT_EQ(r.witnessesDropped, 0u);
  for (const Witness& w : scratch.witnesses()) EXPECT_TRUE(w.isExact());

  s.maxWitnesses = 3;
  const QueryResult capped = collide(tree, p.a, tree, p.b, s, scratch);
  EXPECT_EQ(capped.witnessCount, 3u);
  EXPECT_EQ(capped.witnessesDropped, expected - 3);
}

TEST(ExactMode, WorkBudgetStopsAndSaysSo) {
  const TriangleMesh mesh = gen::makeTorus(1.0, 0.35, 40, 20);
  AdbTree tree(mesh);
  QueryScratch scratch;
  QuerySettings s = test::exactSettings();
  s.stopAtFirstHit = false;
  s.budgetNodePairs = 50;
  std::mt19937_64 rng(test::kSeed);
  const PosePair p = benchmarkPoses(mesh.bounds(), 0.8, rng);
  const QueryResult r = collide(tree, p.a, tree, p.b, s, scratch);
  EXPECT_EQ(r.stop, StopReason::WorkBudget);
  EXPECT_LE(r.nodePairs, 50u);
}

}  // namespace
}  // namespace adb
