// adb's pair queries on worker threads (FrameSettings::threads): the same simulation to the
// bit at 1, 2 and all hardware threads, with and without a node-pair budget; the step's
// statistics say what ran in parallel; bad thread counts are refused by name.
#include <gtest/gtest.h>

#include <numeric>
#include <string>
#include <vector>

#include "adb/support/mesh_generators.h"
#include "bullet_world.h"

namespace adb {
namespace {

using test::World;

// Twelve concave bodies in three layers: many mesh-mesh pairs at once, for the pool to share.
void addPile(World& w) { test::addConcavePile(w, 12, 4); }

struct PileRun {
  std::vector<std::uint64_t> hashes;  // the bodies after every step
  std::uint32_t threads = 0;          // FrameStats::threads of the last step
  double parallelMicros = 0.0;        // summed over the steps
  double busyMicros = 0.0;            // every thread's, summed over the steps
  std::uint64_t nodePairs = 0;
  std::uint32_t cutPairs = 0;         // summed over the steps
};

PileRun runPile(FrameSettings f, int threads, int steps = 60) {
  f.threads = threads;
  World w(test::Dispatch::Adb, f);
  w.adbDispatcher->setFrameSettings(f);  // exactly `threads`, whatever ADB_TEST_THREADS says
  addPile(w);
  PileRun r;
  for (int step = 0; step < steps; ++step) {
    w.step();
    const FrameStats& s = w.adbDispatcher->lastFrameStats();
    r.threads = s.threads;
    r.parallelMicros += s.parallelMicros;
    r.busyMicros += std::accumulate(s.threadBusyMicros.begin(), s.threadBusyMicros.end(), 0.0);
    r.nodePairs += s.nodePairs;
    r.cutPairs += s.cutPairs;
    r.hashes.push_back(test::hashBodies(w.bodies));
  }
  return r;
}

void expectSameTrajectory(const PileRun& a, const PileRun& b) {
  ASSERT_EQ(a.hashes.size(), b.hashes.size());
  for (std::size_t step = 0; step < a.hashes.size(); ++step) {
    ASSERT_EQ(a.hashes[step], b.hashes[step]) << "trajectories part at step " << step + 1;
  }
  EXPECT_EQ(a.nodePairs, b.nodePairs);
}

TEST(Threads, WithoutABudgetTheSimulationIsTheSameAtAnyThreadCount) {
  const PileRun one = runPile(FrameSettings{}, 1);
  ASSERT_GT(one.nodePairs, 10000u) << "the pile must collide for this test to mean anything";
  EXPECT_EQ(one.threads, 1u);
  EXPECT_EQ(one.parallelMicros, 0.0);
  const PileRun two = runPile(FrameSettings{}, 2);
  EXPECT_EQ(two.threads, 2u);
  EXPECT_GT(two.parallelMicros, 0.0);
  EXPECT_GT(two.busyMicros, 0.0);
  expectSameTrajectory(one, two);
  expectSameTrajectory(one, runPile(FrameSettings{}, 0));  // all hardware threads
}

// Without a budget the pairs of a mesh with a plane, a box, a sphere or a capsule gather their
// contacts on the pool (closed form; only their writing stays on the stepping thread): the
// same simulation at 1 and 2 threads. With no mesh-mesh pair in the world, the pool's time
// says that the gathering ran there.
TEST(Threads, PairsWithPrimitivesGatherOnThePoolWithTheSameSimulation) {
  const auto run = [](int threads) {
    FrameSettings f;
    f.threads = threads;
    World w(test::Dispatch::Adb, f);
    w.adbDispatcher->setFrameSettings(f);
    w.add(std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), 0), 0, btVector3(0, 0, 0));
    w.add(std::make_unique<btBoxShape>(btVector3(0.5, 2, 5)), 0, btVector3(-2.5, 0, 0));
    const auto torus = MeshData::build(test::flatTorus(0.4, 0.15));
    for (int i = 0; i < 4; ++i) {  // 1.3 apart: no two tori touch; the first leans on the wall
      w.add(torus, 1, btVector3(btScalar(-1.45 + 1.3 * i), btScalar(0.3 + 0.1 * i), 0))
          ->setActivationState(DISABLE_DEACTIVATION);
    }
    w.add(std::make_unique<btSphereShape>(btScalar(0.25)), 1, btVector3(btScalar(-0.15), 1, 0));
    w.add(std::make_unique<btCapsuleShape>(btScalar(0.1), btScalar(0.8)), 1,
          btVector3(btScalar(1.15), 1, btScalar(0.3)));
    PileRun r;
    for (int step = 0; step < 90; ++step) {
      w.step();
      const FrameStats& s = w.adbDispatcher->lastFrameStats();
      EXPECT_EQ(s.pairs, 0u) << "no mesh-mesh pair may form in this scene";
      r.parallelMicros += s.parallelMicros;
      r.nodePairs += s.nodePairs;
      r.hashes.push_back(test::hashBodies(w.bodies));
    }
    return r;
  };
  const PileRun one = run(1);
  ASSERT_GT(one.nodePairs, 1000u) << "the pairs with the primitives must touch triangles";
  EXPECT_EQ(one.parallelMicros, 0.0);
  const PileRun two = run(2);
  EXPECT_GT(two.parallelMicros, 0.0) << "the pairs' contacts were not gathered on the pool";
  expectSameTrajectory(one, two);
}

// A budgeted step's queries run in rounds whose grants are decided before they run: on the
// pool, and the same grants, contacts and trajectories at any thread count.
TEST(Threads, UnderANodePairBudgetTheSimulationIsTheSameAtAnyThreadCount) {
  FrameSettings f;
  f.budgetNodePairs = 3000;
  const PileRun one = runPile(f, 1);
  EXPECT_GT(one.cutPairs, 0u) << "the budget must bind for this test to mean anything";
  EXPECT_EQ(one.parallelMicros, 0.0);
  const PileRun two = runPile(f, 2);
  EXPECT_GT(two.parallelMicros, 0.0) << "budgeted queries ran on the stepping thread alone";
  expectSameTrajectory(one, two);
  expectSameTrajectory(one, runPile(f, 0));
}

// The paper's best-first traversal with a quality target, refined by re-running: the same.
TEST(Threads, UnderABudgetWithAQualityTargetTheSimulationIsTheSameAtOneAndTwoThreads) {
  FrameSettings f;
  f.budgetNodePairs = 3000;
  f.kMin = 4;
  const PileRun one = runPile(f, 1, 40);
  EXPECT_GT(one.cutPairs, 0u) << "the budget must bind for this test to mean anything";
  expectSameTrajectory(one, runPile(f, 2, 40));
}

TEST(Threads, BadCountsAreRefusedByName) {
  World w;
  for (int threads : {-1, kMaxThreads + 1}) {
    FrameSettings f;
    f.threads = threads;
    try {
      w.adbDispatcher->setFrameSettings(f);
      ADD_FAILURE() << threads << " threads were accepted";
    } catch (const SettingsError& e) {
      EXPECT_NE(std::string(e.what()).find("threads"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace adb
