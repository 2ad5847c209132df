// The box-first baseline (box_first.h) on a generated knot: run to the end it gives exactly
// the tree's exact answer, at random poses and at grazing contacts, and on two different
// models (their two trees); with a zero budget it answers exactly like the root boxes; and
// once its queue has grown, repeating the queries allocates nothing.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <limits>
#include <memory>
#include <new>
#include <random>
#include <vector>

#include "adb/support/benchmark_poses.h"
#include "adb/support/mesh_generators.h"
#include "adb/core/query.h"
#include "adb_method.h"
#include "box_first.h"
#include "root_boxes_method.h"

// Counts every allocation of this test program, so that a test can check that a stretch of
// code allocates nothing (the counter is only read around the queries under test).
namespace {
std::atomic<long long> g_allocations{0};
}  // namespace

// GCC cannot see that this operator new and the operator delete below are a pair over
// malloc/free, and warns at every inlined delete.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t size) {
  ++g_allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace adb::tradeoff {
namespace {

constexpr double kNoBudget = std::numeric_limits<double>::infinity();

// A small run: the knot at distances from deep overlap to apart, a few rotations each.
std::vector<PosePair> smallRun(const Aabb& bounds) {
  std::mt19937_64 rng(11);
  std::vector<PosePair> poses;
  for (double d : {0.3, 0.6, 0.9, 1.2, 1.5, 1.9}) {
    for (int r = 0; r < 15; ++r) poses.push_back(benchmarkPoses(bounds, d, rng));
  }
  return poses;
}

bool exactCollides(const AdbTree& tree, const PosePair& p, QueryScratch& scratch) {
  QuerySettings exact;
  exact.mode = QueryMode::Exact;
  return collide(tree, p.a, tree, p.b, exact, scratch).collides;
}

// Grazing contacts, where an answer hangs on one or two triangle pairs: per rotation, B is
// slid along the line of centres and the last touching and first free offsets are found by
// bisection (to 1e-9 of the model's size) with the tree's exact mode.
std::vector<PosePair> grazingPoses(const AdbTree& tree, const Aabb& bounds) {
  std::mt19937_64 rng(5);
  const double size = bounds.extent().maxCoeff();
  QueryScratch scratch;
  std::vector<PosePair> poses;
  for (int r = 0; r < 60; ++r) {
    const PosePair start = benchmarkPoses(bounds, 0.0, rng);  // centres together: touching
    const auto slid = [&](double offset) {
      PosePair p = start;
      p.b.translation.x() += offset;
      return p;
    };
    double touching = 0.0, apart = 2.0 * size;  // boxes apart at a whole diagonal and more
    if (!exactCollides(tree, slid(touching), scratch) ||
        exactCollides(tree, slid(apart), scratch)) {
      continue;  // no bracket for this rotation
    }
    while (apart - touching > 1e-9 * size) {
      const double mid = 0.5 * (touching + apart);
      (exactCollides(tree, slid(mid), scratch) ? touching : apart) = mid;
    }
    poses.push_back(slid(touching));
    poses.push_back(slid(apart));
  }
  return poses;
}

struct Knot {
  Model model{"knot", 0, gen::makeModel("knot", 2000)};
  std::shared_ptr<SharedTree> tree = std::make_shared<SharedTree>();
  std::vector<PosePair> poses = smallRun(model.mesh.bounds());
};

TEST(PeerBoxFirst, WithoutABudgetAgreesWithExactModeOnEveryQuery) {
  Knot k;
  BoxFirstMethod boxFirst(k.tree, kNoBudget);
  boxFirst.prepare(k.model, k.model);
  QuerySettings exact;
  exact.mode = QueryMode::Exact;
  QueryScratch scratch;
  const AdbTree& tree = k.tree->treeFor(k.model);
  int hits = 0;
  for (std::size_t i = 0; i < k.poses.size(); ++i) {
    const PosePair& p = k.poses[i];
    const Answer answer = boxFirst.query(p.a, p.b);
    const QueryResult reference = collide(tree, p.a, tree, p.b, exact, scratch);
    EXPECT_EQ(answer.collides, reference.collides) << "pose " << i;
    EXPECT_EQ(answer.confidence, 1.0) << "pose " << i << ": it ran to the end";
    EXPECT_GE(answer.nodePairs, 1) << "pose " << i;
    hits += answer.collides ? 1 : 0;
  }
  // Both answers occur often: the agreement is not vacuous.
  EXPECT_GT(hits, 10);
  EXPECT_LT(hits, static_cast<int>(k.poses.size()) - 10);
}

TEST(PeerBoxFirst, WithoutABudgetAgreesWithExactModeAtGrazingContacts) {
  Knot k;
  BoxFirstMethod boxFirst(k.tree, kNoBudget);
  boxFirst.prepare(k.model, k.model);
  const AdbTree& tree = k.tree->treeFor(k.model);
  const std::vector<PosePair> poses = grazingPoses(tree, k.model.mesh.bounds());
  ASSERT_GE(poses.size(), 60u);
  QueryScratch scratch;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    // Even poses touch, odd ones are free by 1e-9 of the model's size.
    EXPECT_EQ(exactCollides(tree, poses[i], scratch), i % 2 == 0) << "pose " << i;
    EXPECT_EQ(boxFirst.query(poses[i].a, poses[i].b).collides, i % 2 == 0) << "pose " << i;
  }
}

// Two different models, each with its own tree (the robot anywhere in the room, and the knot
// against the gears at Zachmann's distances): run to the end, box-first still gives exactly
// the exact mode's answer on the two trees.
TEST(PeerBoxFirst, OnTwoDifferentModelsAgreesWithExactMode) {
  struct Pair {
    Model a, b;
    bool inside;
  };
  const Pair pairs[] = {
      {Model{"room", 0, gen::makeFixedModel("room")},
       Model{"robot", 1, gen::makeFixedModel("robot")}, true},
      {Model{"knot", 2, gen::makeModel("knot", 2000)},
       Model{"gears", 3, gen::makeModel("gears", 1000)}, false},
  };
  for (const Pair& pair : pairs) {
    auto shared = std::make_shared<SharedTree>();
    BoxFirstMethod boxFirst(shared, kNoBudget);
    boxFirst.prepare(pair.a, pair.b);
    const AdbTree& treeA = shared->treeFor(pair.a);
    const AdbTree& treeB = shared->treeFor(pair.b);
    ASSERT_NE(&treeA, &treeB);
    QuerySettings exact;
    exact.mode = QueryMode::Exact;
    QueryScratch scratch;
    std::mt19937_64 rng(17);
    int hits = 0;
    const int n = 150;
    for (int i = 0; i < n; ++i) {
      const PosePair p = pair.inside ? insidePoses(pair.a.mesh.bounds(), pair.b.mesh.bounds(), rng)
                                     : benchmarkPoses(pair.a.mesh.bounds(), pair.b.mesh.bounds(),
                                                      0.3 + 1.5 * i / n, rng);
      const Answer answer = boxFirst.query(p.a, p.b);
      const QueryResult reference = collide(treeA, p.a, treeB, p.b, exact, scratch);
      EXPECT_EQ(answer.collides, reference.collides) << pair.a.label << " pose " << i;
      hits += answer.collides ? 1 : 0;
    }
    EXPECT_GT(hits, 10) << pair.a.label;
    EXPECT_LT(hits, n - 10) << pair.a.label;
  }
}

TEST(PeerBoxFirst, AZeroBudgetAnswersLikeTheRootBoxes) {
  Knot k;
  BoxFirstMethod boxFirst(k.tree, 0.0);
  boxFirst.prepare(k.model, k.model);
  RootBoxesMethod rootBoxes;
  rootBoxes.prepare(k.model, k.model);
  int overlapping = 0;
  for (std::size_t i = 0; i < k.poses.size(); ++i) {
    const PosePair& p = k.poses[i];
    const Answer cut = boxFirst.query(p.a, p.b);
    const Answer roots = rootBoxes.query(p.a, p.b);
    EXPECT_EQ(cut.collides, roots.collides) << "pose " << i;
    EXPECT_EQ(roots.confidence, 0.5);
    // Cut before the first pop ("collides", no estimate), or decided at the roots (apart).
    EXPECT_EQ(cut.confidence, cut.collides ? 0.5 : 1.0) << "pose " << i;
    EXPECT_EQ(cut.nodePairs, 1) << "pose " << i << ": nothing beyond the roots";
    overlapping += roots.collides ? 1 : 0;
  }
  EXPECT_GT(overlapping, 10);
  EXPECT_LT(overlapping, static_cast<int>(k.poses.size()));
}

TEST(PeerBoxFirst, RepeatedQueriesDoNotAllocate) {
  Knot k;
  BoxFirstMethod boxFirst(k.tree, kNoBudget);
  boxFirst.prepare(k.model, k.model);
  for (const PosePair& p : k.poses) boxFirst.query(p.a, p.b);  // the queue grows here
  const long long before = g_allocations.load();
  int hits = 0;
  for (const PosePair& p : k.poses) hits += boxFirst.query(p.a, p.b).collides ? 1 : 0;
  EXPECT_EQ(g_allocations.load() - before, 0);
  EXPECT_GT(hits, 0);  // the queries did real work
}

}  // namespace
}  // namespace adb::tradeoff
