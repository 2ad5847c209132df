// ADB mode: error rate against the exact answer over the benchmark distances, monotone
// confidence under growing budgets, witnesses, thread safety, no allocation in steady state.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <new>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "adb/support/mesh_generators.h"
#include "adb/core/tree.h"
#include "test_support.h"

// Counts every allocation of this test program, so a test can assert that a stretch of code
// allocates nothing. Replacing the global operator new is the only way to see allocations
// made inside the library.
namespace {
std::atomic<std::size_t> g_allocations{0};
}  // namespace

// GCC cannot see that this operator new and the operator delete below are a pair over
// malloc/free, and warns at every inlined delete.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace adb {
namespace {

struct ErrorRate {
  int counted = 0;  // queries whose root boxes overlap (the paper counts only those)
  int wrong = 0;
  double percent() const { return counted ? 100.0 * wrong / counted : 0.0; }
};

// The paper's error measure at p_min 0.99, k_min 10 over distances 0.4..2.0.
ErrorRate measureErrorRate(const TriangleMesh& mesh, int posesPerDistance,
                           const QuerySettings& settings) {
  const AdbTree tree(mesh);
  QueryScratch scratch;
  std::mt19937_64 rng(test::kSeed);
  ErrorRate e;
  for (int step = 0; step <= 16; ++step) {
    const double d = 0.4 + 0.1 * step;
    for (int i = 0; i < posesPerDistance; ++i) {
      const PosePair p = benchmarkPoses(mesh.bounds(), d, rng);
      const QueryResult exact = collide(tree, p.a, tree, p.b, test::exactSettings(), scratch);
      const QueryResult fast = collide(tree, p.a, tree, p.b, settings, scratch);
      if (exact.nodePairs <= 1 && !exact.collides) continue;  // root boxes apart: not counted
      ++e.counted;
      e.wrong += exact.collides != fast.collides ? 1 : 0;
    }
  }
  return e;
}

// The bound: the paper reports 1.5-2.1 % mean error at these settings on its CAD models; our
// generated models are measured in docs/core-results.md. The bound is the paper's worst
// reported mean (3.2 %, distances 1 to 2) plus the sampling error of ~500 queries (2 sigma of
// a 3 % proportion: 1.5 points).
constexpr double kMaxErrorPercent = 4.7;

void expectErrorRateBelowBound(const std::string& model) {
  const ErrorRate e =
      measureErrorRate(gen::makeModel(model, 20000), 30, test::adbSettings(0.99, 10));
  // Most of the 510 poses have overlapping root boxes; far fewer would make the rate noise.
  EXPECT_GT(e.counted, 300) << model;
  EXPECT_LE(e.percent(), kMaxErrorPercent) << model << ": " << e.wrong << " of " << e.counted;
}

TEST(AdbErrorRate, TorusKnotBelowBound) { expectErrorRateBelowBound("knot"); }
TEST(AdbErrorRate, PipesBelowBound) { expectErrorRateBelowBound("pipes"); }
TEST(AdbErrorRate, GearsBelowBound) { expectErrorRateBelowBound("gears"); }
TEST(AdbErrorRate, LockBelowBound) { expectErrorRateBelowBound("lock"); }
TEST(AdbErrorRate, TorusBelowBound) { expectErrorRateBelowBound("torus"); }

TEST(AdbErrorRate, LowerQualitySettingsMakeMoreErrorsNotFewer) {
  // The paper's trend (Fig. 11): p_min 0.5 / k_min 1 errs at least as often as 0.99 / 10,
  // up to sampling noise.
  const TriangleMesh mesh = gen::makeModel("knot", 20000);
  const ErrorRate strict = measureErrorRate(mesh, 20, test::adbSettings(0.99, 10));
  const ErrorRate loose = measureErrorRate(mesh, 20, test::adbSettings(0.5, 1));
  EXPECT_GE(loose.percent() + 1.0, strict.percent());
}

// Exact mode completes with certainty; cut by a budget before any hit it answers "no" (the
// baseline without a model) with the estimate's 1 - P as its confidence.
TEST(AdbConfidence, ExactModeCutSaysNoWithTheEstimate) {
  const TriangleMesh mesh = gen::makeModel("knot", 5000);
  const AdbTree tree(mesh);
  QueryScratch scratch;
  std::mt19937_64 rng(test::kSeed);
  int cut = 0;
  for (int i = 0; i < 20; ++i) {
    const PosePair p = benchmarkPoses(mesh.bounds(), 0.4 + 0.08 * i, rng);
    for (std::uint64_t budget : {0ull, 10ull, 100ull, 1000ull}) {
      QuerySettings s = test::exactSettings();
      s.budgetNodePairs = budget;
      const QueryResult r = collide(tree, p.a, tree, p.b, s, scratch);
      if (r.stop != StopReason::WorkBudget) continue;
      ++cut;
      EXPECT_FALSE(r.collides);
      EXPECT_TRUE(r.confidence >= 0.0 && r.confidence < 1.0) << r.confidence;
    }
    QuerySettings s = test::exactSettings();
    EXPECT_EQ(collide(tree, p.a, tree, p.b, s, scratch).confidence, 1.0);
  }
  EXPECT_GT(cut, 20);
}

// Answers grouped by their confidence, as the study's reliability diagram does: 10 bins, the
// expected calibration error (ECE) and the wrong answers among the confident ones.
struct Calibration {
  int answers = 0, wrong = 0;
  int colliding = 0;                      // the truth among the answers
  int confident = 0, confidentWrong = 0;  // confidence >= 0.99
  double ece = 0.0;
};

// How the second body of a calibration's queries is placed: Zachmann's distances, or anywhere
// inside the first's box (a robot in a room).
enum class Placement { Distances, Inside };

// Mesh A against mesh B under `budget` node pairs at the defaults, 17 x `perStep` poses.
Calibration calibrate(const TriangleMesh& meshA, const TriangleMesh& meshB, Placement placement,
                      std::uint64_t budget, int perStep = 20) {
  const AdbTree treeA(meshA), treeB(meshB);
  QueryScratch scratch;
  std::mt19937_64 rng(test::kSeed);
  Calibration c;
  double conf[10] = {}, right[10] = {};
  for (int step = 0; step <= 16; ++step) {
    for (int i = 0; i < perStep; ++i) {
      const PosePair p =
          placement == Placement::Inside
              ? insidePoses(meshA.bounds(), meshB.bounds(), rng)
              : benchmarkPoses(meshA.bounds(), meshB.bounds(), 0.4 + 0.1 * step, rng);
      const QueryResult truth =
          collide(treeA, p.a, treeB, p.b, test::exactSettings(), scratch);
      if (!truth.collides && truth.nodePairs <= 1) continue;  // root boxes apart: not counted
      QuerySettings s = test::adbSettings();
      s.budgetNodePairs = budget;
      const QueryResult r = collide(treeA, p.a, treeB, p.b, s, scratch);
      const bool wrong = r.collides != truth.collides;
      ++c.answers;
      c.colliding += truth.collides ? 1 : 0;
      c.wrong += wrong ? 1 : 0;
      if (r.confidence >= 0.99) {
        ++c.confident;
        c.confidentWrong += wrong ? 1 : 0;
      }
      const int bin = std::min(9, static_cast<int>(r.confidence * 10.0));
      conf[bin] += r.confidence;
      right[bin] += wrong ? 0.0 : 1.0;
    }
  }
  for (int b = 0; b < 10; ++b) c.ece += std::abs(right[b] - conf[b]);
  c.ece /= std::max(1, c.answers);
  return c;
}

Calibration calibrate(const std::string& model, std::uint64_t budget) {
  const TriangleMesh mesh = gen::makeModel(model, 5000);
  return calibrate(mesh, mesh, Placement::Distances, budget);
}

TEST(AdbConfidence, ConfidentAnswersAreRightAtAboutTheClaimedRate) {
  // Claimed: >= 99 % right. Allowed: 98 % (a 1-point margin for ~300 samples per model).
  for (const char* model : {"knot", "pipes", "torus"}) {
    const Calibration c = calibrate(model, std::numeric_limits<std::uint64_t>::max());
    ASSERT_GT(c.confident, 200) << model;
    EXPECT_LE(c.confidentWrong, c.confident / 50) << model;
  }
}

// Cut queries answer with the more probable side at a calibrated probability. The fitted
// estimate's ECE on the generated models is 0.02 to 0.10 over the states a budget stops a
// query in (docs/probability-model.md), lower over all answers since complete ones are
// certain. Bound: 0.10 per budget, for ~300 answers per model (a bin's sampling error is
// about 0.03). The answers must also beat, on the same queries, the best answer without a
// model, "collision whenever the root boxes overlap" (wrong for every pose that does not
// collide), and be wrong less than a quarter of the time (the paper's "no when cut" is
// wrong for 58 to 79 % of tight-budget queries on CAD meshes, issue 10).
TEST(AdbConfidence, CutAnswersFollowTheEstimateAndAreCalibrated) {
  for (const char* model : {"knot", "pipes", "torus"}) {
    for (std::uint64_t budget : {8ull, 64ull, 512ull}) {
      const Calibration c = calibrate(model, budget);
      EXPECT_LE(c.ece, 0.10) << model << " budget " << budget;
      const int trivial = c.answers - c.colliding;  // "collision" whenever the roots overlap
      EXPECT_LT(c.wrong, trivial) << model << " budget " << budget;
      EXPECT_LT(c.wrong, c.answers / 4) << model << " budget " << budget;
    }
  }
}

// Issue 43: a confidence that tells the truth under any budget, on pairs of different models
// that the estimate was never fitted on (studies/calibrate fits on other pairs: the robot arm
// in the room, knot and gears, slivers and lock, the arm and the pipes). A low-poly body
// anywhere in the low-poly room, and slivers against a dense sphere. Before issue 43, cut
// early, the pipes in the room were answered "no" 80 % wrong (ECE 0.71 at 8 node pairs), the
// arm in the room 47 % wrong with every wrong answer at >= 0.99: the cell model is blind to
// large flat triangles and read as "no". Bounds: ECE 0.12 for ~340 answers (a bin's sampling
// error alone is about 0.03-0.05), 0.2 at 8 node pairs (two expansions: the estimate can only
// say the base rate of what it saw; measured 0.15-0.19 here and in adb-calibrate's check),
// confident wrong answers at most 1 % of all answers.
TEST(AdbConfidence, HeldOutPairsOfDifferentModelsAreCalibratedUnderBudgets) {
  const TriangleMesh room = gen::makeFixedModel("room");
  const TriangleMesh pipes = gen::makeModel("pipes", 400);
  const TriangleMesh sphere = gen::makeModel("sphere", 1000);
  const TriangleMesh slivers = gen::makeModel("slivers", 4000);
  struct HeldOut {
    const char* name;
    const TriangleMesh& a;
    const TriangleMesh& b;
    Placement placement;
  };
  for (const HeldOut& pair : {HeldOut{"room+pipes-400", room, pipes, Placement::Inside},
                              HeldOut{"sphere+slivers", sphere, slivers, Placement::Distances}}) {
    for (std::uint64_t budget : {8ull, 32ull, 128ull}) {
      const Calibration c = calibrate(pair.a, pair.b, pair.placement, budget);
      ASSERT_GT(c.answers, 250) << pair.name;
      EXPECT_LE(c.ece, budget == 8 ? 0.2 : 0.12) << pair.name << " budget " << budget;
      EXPECT_LE(c.confidentWrong * 100, c.answers) << pair.name << " budget " << budget;
    }
  }
}

TEST(AdbConfidence, AnExactHitMakesACollisionCertainWhateverStops) {
  // With every hit collected, the traversal can reach k_min after an exact hit: certain.
  const TriangleMesh mesh = gen::makeModel("knot", 5000);
  BuildSettings b;
  b.maxLeafTriangles = 1;
  const AdbTree tree(mesh, b);
  QueryScratch scratch;
  QuerySettings s = test::adbSettings(0.9, 2);
  s.stopAtFirstHit = false;
  std::mt19937_64 rng(test::kSeed);
  int withHit = 0;
  for (int i = 0; i < 200; ++i) {
    const PosePair p = benchmarkPoses(mesh.bounds(), 0.4 + 0.008 * i, rng);
    const QueryResult r = collide(tree, p.a, tree, p.b, s, scratch);
    bool exact = false;
    for (const Witness& w : scratch.witnesses()) exact = exact || w.isExact();
    if (!exact) continue;
    ++withHit;
    EXPECT_TRUE(r.collides);
    EXPECT_EQ(r.confidence, 1.0) << "pose " << i << " stopped by " << toString(r.stop);
  }
  EXPECT_GT(withHit, 5);
}

TEST(AdbWitnesses, NoCollisionAnswersCarryNoWitnesses) {
  const TriangleMesh mesh = gen::makeModel("pipes", 5000);
  const AdbTree tree(mesh);
  QueryScratch scratch;
  std::mt19937_64 rng(test::kSeed);
  for (int i = 0; i < 300; ++i) {
    const PosePair p = benchmarkPoses(mesh.bounds(), 0.4 + 0.006 * i, rng);
    for (std::uint64_t budget : {16ull, 256ull, 1ull << 30}) {
      QuerySettings s = test::adbSettings();
      s.budgetNodePairs = budget;
      const QueryResult r = collide(tree, p.a, tree, p.b, s, scratch);
      if (!r.collides) {
        EXPECT_EQ(r.witnessCount, 0u);
      }
      EXPECT_EQ(r.witnessCount, scratch.witnesses().size());
    }
  }
}

TEST(AdbWitnesses, CollisionAnswersCarryAcceptedPairs) {
  const TriangleMesh mesh = gen::makeModel("knot", 20000);
  const AdbTree tree(mesh);
  QueryScratch scratch;
  std::mt19937_64 rng(test::kSeed);
  int collisions = 0;
  for (int i = 0; i < 30; ++i) {
    const PosePair p = benchmarkPoses(mesh.bounds(), 0.4, rng);
    const QueryResult r = collide(tree, p.a, tree, p.b, test::adbSettings(), scratch);
    if (!r.collides) continue;
    ++collisions;
    ASSERT_GE(r.witnessCount, 1u);
    for (const Witness& w : scratch.witnesses()) {
      EXPECT_TRUE(w.isExact() || w.probability > 0.99f);
      EXPECT_LT(w.nodeA, tree.nodes().size());
      EXPECT_LT(w.nodeB, tree.nodes().size());
    }
  }
  EXPECT_GT(collisions, 20);
}

// Without pruning, a completed ADB traversal has tested every overlapping triangle pair: it
// must give the exact mode's answer on every pose (including those where the paper's rule
// errs) and find the same intersecting triangle pairs, only in another order.
TEST(AdbUnpruned, CompletedTraversalIsExact) {
  const TriangleMesh mesh = gen::makeModel("pipes", 5000);
  const AdbTree tree(mesh);
  QueryScratch adbScratch, exactScratch;
  QuerySettings adb = test::adbSettings(0.99, std::numeric_limits<int>::max());
  adb.pruneImprobable = false;
  adb.stopAtFirstHit = false;
  adb.maxWitnesses = 1u << 20;
  QuerySettings exact = test::exactSettings();
  exact.stopAtFirstHit = false;
  exact.maxWitnesses = 1u << 20;
  std::mt19937_64 rng(test::kSeed);
  int collisions = 0;
  for (int i = 0; i < 150; ++i) {
    const PosePair p = benchmarkPoses(mesh.bounds(), 0.4 + 0.01 * i, rng);
    const QueryResult r = collide(tree, p.a, tree, p.b, adb, adbScratch);
    const QueryResult e = collide(tree, p.a, tree, p.b, exact, exactScratch);
    ASSERT_EQ(r.stop, StopReason::Completed) << "pose " << i;
    EXPECT_EQ(r.collides, e.collides) << "pose " << i;
    EXPECT_EQ(r.confidence, 1.0) << "pose " << i;
    EXPECT_TRUE(adbScratch.openPairs().empty());
    std::vector<std::pair<std::uint32_t, std::uint32_t>> a, b;
    for (const Witness& w : adbScratch.witnesses()) {
      if (w.isExact()) a.emplace_back(w.triangleA, w.triangleB);
    }
    for (const Witness& w : exactScratch.witnesses()) b.emplace_back(w.triangleA, w.triangleB);
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b) << "pose " << i;
    collisions += e.collides;
  }
  EXPECT_GT(collisions, 20);
  EXPECT_LT(collisions, 140);
}

// The table key changes the order, never what is pruned or accepted: run to completion (no
// k_min, no first-hit stop) with pruning on, both keys evaluate the same node pairs, accept the
// same number and find the same triangle pairs.
TEST(AdbKeys, TableAndEq3PruneAndAcceptTheSamePairs) {
  const TriangleMesh mesh = gen::makeModel("knot", 5000);
  const AdbTree tree(mesh);
  QueryScratch tableScratch, eq3Scratch;
  QuerySettings table = test::adbSettings(0.9, std::numeric_limits<int>::max());
  table.stopAtFirstHit = false;
  table.maxWitnesses = 1u << 20;
  table.adbKey = AdbKey::Table;
  QuerySettings eq3 = table;
  eq3.adbKey = AdbKey::Eq3;
  std::mt19937_64 rng(test::kSeed);
  std::uint64_t accepted = 0;
  for (int i = 0; i < 100; ++i) {
    const PosePair p = benchmarkPoses(mesh.bounds(), 0.4 + 0.015 * i, rng);
    const QueryResult t = collide(tree, p.a, tree, p.b, table, tableScratch);
    const QueryResult e = collide(tree, p.a, tree, p.b, eq3, eq3Scratch);
    EXPECT_EQ(t.nodePairs, e.nodePairs) << "pose " << i;
    EXPECT_EQ(t.triangleTests, e.triangleTests) << "pose " << i;
    EXPECT_EQ(t.collisionPairs, e.collisionPairs) << "pose " << i;
    EXPECT_EQ(t.collides, e.collides) << "pose " << i;
    std::vector<std::pair<std::uint32_t, std::uint32_t>> a, b;
    for (const Witness& w : tableScratch.witnesses()) a.emplace_back(w.triangleA, w.triangleB);
    for (const Witness& w : eq3Scratch.witnesses()) b.emplace_back(w.triangleA, w.triangleB);
    std::sort(a.begin(), a.end());
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b) << "pose " << i;
    accepted += t.collisionPairs;
  }
  EXPECT_GT(accepted, 100u);  // acceptances were compared, not only their absence
}

// A cut unpruned traversal leaves its frontier: valid node pairs with estimates in [0, 1],
// fewer of them as the budget grows to completion.
TEST(AdbUnpruned, CutTraversalLeavesItsOpenPairs) {
  const TriangleMesh mesh = gen::makeModel("knot", 5000);
  const AdbTree tree(mesh);
  QueryScratch scratch;
  QuerySettings s = test::adbSettings(0.99, std::numeric_limits<int>::max());
  s.pruneImprobable = false;
  s.stopAtFirstHit = false;
  std::mt19937_64 rng(test::kSeed);
  const PosePair p = benchmarkPoses(mesh.bounds(), 0.5, rng);
  s.budgetNodePairs = 64;
  const QueryResult cut = collide(tree, p.a, tree, p.b, s, scratch);
  ASSERT_EQ(cut.stop, StopReason::WorkBudget);
  ASSERT_FALSE(scratch.openPairs().empty());
  for (const OpenPair& o : scratch.openPairs()) {
    EXPECT_LT(o.a, tree.nodes().size());
    EXPECT_LT(o.b, tree.nodes().size());
    EXPECT_GE(o.p, 0.0f);
    EXPECT_LE(o.p, 1.0f);
    EXPECT_GE(o.upper, 0.0f);
    EXPECT_LE(o.upper, 1.0f);
  }
  s.budgetNodePairs = std::numeric_limits<std::uint64_t>::max();
  const QueryResult full = collide(tree, p.a, tree, p.b, s, scratch);
  EXPECT_EQ(full.stop, StopReason::Completed);
  EXPECT_TRUE(scratch.openPairs().empty());
  // An exact-mode query cut by its budget reports its depth-first stack, estimated when it
  // stopped (test_contact_sampling.cpp checks the estimates).
  QuerySettings e = test::exactSettings();
  e.budgetNodePairs = 8;
  ASSERT_EQ(collide(tree, p.a, tree, p.b, e, scratch).stop, StopReason::WorkBudget);
  EXPECT_FALSE(scratch.openPairs().empty());
}

TEST(AdbThreads, ConcurrentQueriesOnSharedTreesMatchSequentialOnes) {
  const TriangleMesh mesh = gen::makeModel("pipes", 10000);
  const AdbTree tree(mesh);
  std::mt19937_64 rng(test::kSeed);
  std::vector<PosePair> poses;
  for (int i = 0; i < 200; ++i) poses.push_back(benchmarkPoses(mesh.bounds(), 0.4 + 0.008 * i, rng));
  const auto runAll = [&](std::vector<QueryResult>& out, QueryMode mode) {
    QueryScratch scratch;
    QuerySettings s = mode == QueryMode::Exact ? test::exactSettings() : test::adbSettings();
    for (const PosePair& p : poses) out.push_back(collide(tree, p.a, tree, p.b, s, scratch));
  };
  for (QueryMode mode : {QueryMode::Adb, QueryMode::Exact}) {
    std::vector<QueryResult> sequential;
    runAll(sequential, mode);
    std::vector<std::vector<QueryResult>> perThread(4);
    std::vector<std::thread> threads;
    for (auto& out : perThread) threads.emplace_back([&, m = mode] { runAll(out, m); });
    for (auto& t : threads) t.join();
    for (const auto& out : perThread) {
      ASSERT_EQ(out.size(), sequential.size());
      for (std::size_t i = 0; i < out.size(); ++i) {
        EXPECT_EQ(out[i].collides, sequential[i].collides);
        EXPECT_EQ(out[i].confidence, sequential[i].confidence);
        EXPECT_EQ(out[i].nodePairs, sequential[i].nodePairs);
      }
    }
  }
}

TEST(AdbAllocation, RepeatedQueriesAllocateNothing) {
  const TriangleMesh mesh = gen::makeModel("knot", 20000);
  const AdbTree tree(mesh);
  QueryScratch scratch;
  std::mt19937_64 rng(test::kSeed);
  std::vector<PosePair> poses;
  for (int i = 0; i < 50; ++i) poses.push_back(benchmarkPoses(mesh.bounds(), 0.3 + 0.04 * i, rng));
  QuerySettings exactAll = test::exactSettings();
  exactAll.stopAtFirstHit = false;
  const QuerySettings modes[] = {test::adbSettings(), test::exactSettings(), exactAll};
  // Warm-up: the scratch grows to the largest of these queries...
  for (const QuerySettings& s : modes) {
    for (const PosePair& p : poses) collide(tree, p.a, tree, p.b, s, scratch);
  }
  // ...after which the same queries allocate nothing.
  const std::size_t before = g_allocations.load();
  for (const QuerySettings& s : modes) {
    for (const PosePair& p : poses) collide(tree, p.a, tree, p.b, s, scratch);
  }
  EXPECT_EQ(g_allocations.load() - before, 0u);
}


// The first and second budgeted queries of a fresh process: the tree is built before it, as
// a user builds theirs before stepping. Runs in a forked child so that the parent can repeat it.
struct ColdAndWarm {
  double coldMicros = 0;
  std::uint64_t coldNodePairs = 0;
  std::uint64_t warmNodePairs = 0;
};

ColdAndWarm firstTwoQueriesOfAFreshProcess(const AdbTree& tree, const Pose& at,
                                           const QuerySettings& settings) {
  int fds[2];
  if (pipe(fds) != 0) {
    ADD_FAILURE() << "pipe failed";
    return {};
  }
  const pid_t child = fork();
  if (child < 0) {
    close(fds[0]);
    close(fds[1]);
    ADD_FAILURE() << "fork failed";
    return {};
  }
  if (child == 0) {
    close(fds[0]);
    QueryScratch first, second;
    const QueryResult cold = collide(tree, Pose{}, tree, at, settings, first);
    const QueryResult warm = collide(tree, Pose{}, tree, at, settings, second);
    const ColdAndWarm out{1e6 * cold.seconds, cold.nodePairs, warm.nodePairs};
    const bool written = write(fds[1], &out, sizeof out) == static_cast<ssize_t>(sizeof out);
    _exit(written ? 0 : 1);
  }
  close(fds[1]);
  ColdAndWarm out;
  const bool read_ok = read(fds[0], &out, sizeof out) == static_cast<ssize_t>(sizeof out);
  close(fds[0]);
  int status = 0;
  waitpid(child, &status, 0);
  EXPECT_TRUE(read_ok && WIFEXITED(status) && WEXITSTATUS(status) == 0);
  return out;
}

TEST(ColdStart, TheFirstBudgetedQueryOfAProcessDoesAsMuchAsTheSecond) {
  // A fresh process's first query. The tables behind the probabilities were built on first
  // use, inside the first query's clock: this query (a torus knot against itself 0.3 apart,
  // under 50 us) evaluated 1 node pair in 520 us and answered from the roots, against 205 node
  // pairs for the second (measured with this test before the tables were built at load; 2.6 ms
  // in issue 37's report). Tolerances: the first does at least half the second's node pairs,
  // and takes at most ten times the budget (the clock is checked between expansions).
  // Each fresh process is a forked child (the tables are built at load, before main, so a
  // child's first query is as cold as the parent's would be). Five of them, judged by the
  // median: this machine stalls a running process now and then (a pure 1 ms loop: 21 of 2,000
  // chunks over 10 ms), and one such stall inside one 50 us query failed CI (834 us), which
  // says nothing of the tables.
  const TriangleMesh mesh = gen::makeModel("knot", 20000);
  const AdbTree tree(mesh);
  const Pose at{Mat3::Identity(), Vec3(0.3, 0, 0)};
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  // Under the sanitizers a process's first touches of memory and code are several times
  // slower again (measured under ASan: 65 node pairs in 93 us against 193; 1 without the
  // tables built at load), as for the time budgets of FrameBudget. The first expansion alone
  // (the trees' first touch of shadow memory: 70 to 700 us under ASan) outlasted a 50 us
  // budget in 6 of 10 runs, and a 150 us one in 4 of 8 (1 node pair against the second's 73,
  // which stops at the quality target), on the query code of a3ec8ef as on this one: under
  // the sanitizers the budget is 500 us (0 of 8 failed), what the release build's 50 us test
  // asks of the tables without the shadow memory's first touch.
  constexpr std::uint64_t kSlack = 3;
  constexpr double kBudgetMicros = 50.0 * 10;
#else
  constexpr std::uint64_t kSlack = 1;
  constexpr double kBudgetMicros = 50.0;
#endif
  QuerySettings settings = test::adbSettings(0.99, 10);
  settings.budgetMicros = kBudgetMicros;
  constexpr int kProcesses = 5;
  std::vector<ColdAndWarm> runs;
  for (int i = 0; i < kProcesses; ++i) runs.push_back(firstTwoQueriesOfAFreshProcess(tree, at, settings));
  std::sort(runs.begin(), runs.end(),
            [](const ColdAndWarm& a, const ColdAndWarm& b) { return a.coldMicros < b.coldMicros; });
  const ColdAndWarm& median = runs[kProcesses / 2];
  EXPECT_GE(2 * kSlack * median.coldNodePairs, median.warmNodePairs) << "cold " << median.coldMicros << " us";
  EXPECT_LT(median.coldMicros, 10.0 * static_cast<double>(kSlack) * settings.budgetMicros);
}


// A scratch's buffers are sized by the trees when it meets them, not by the first query:
// exact-mode queries from a far pose to deep overlaps, witnesses capped at their default,
// never grow it past what the first (which found nothing) reserved.
TEST(ColdStart, AnExactScratchIsSizedByTheTreesNotByItsFirstQuery) {
  const TriangleMesh mesh = gen::makeModel("knot", 20000);
  const AdbTree tree(mesh);
  QuerySettings settings = test::exactSettings();
  settings.stopAtFirstHit = false;  // fill the witnesses (64 by default)
  QueryScratch scratch;
  const QueryResult far =
      collide(tree, Pose{}, tree, Pose{Mat3::Identity(), Vec3(50, 0, 0)}, settings, scratch);
  ASSERT_FALSE(far.collides);
  const std::size_t sized = scratch.capacityBytes();
  EXPECT_GT(sized, 0u);
  std::mt19937_64 rng(test::kSeed);
  int collided = 0;
  for (int i = 0; i < 40; ++i) {
    const PosePair p = benchmarkPoses(mesh.bounds(), 0.1 + 0.05 * i, rng);
    collided += collide(tree, p.a, tree, p.b, settings, scratch).collides ? 1 : 0;
  }
  EXPECT_GT(collided, 5);
  EXPECT_EQ(scratch.capacityBytes(), sized);
}


// Meshes as they come (issue 37): a low-poly pipe bundle (384 triangles, thin walls side by
// side) and a cylinder of 51:1 slivers, each against itself at the benchmark's distances,
// every answer checked by the brute force. The paper's rules (pairs of p = 0 pruned, any
// inner pair accepted) answered wrongly and confidently there: measured with this test,
// 5.5 % of the pipe poses "collision" where nothing touches. The defaults must answer every
// pose right when no budget cuts them.
struct Answers {
  int poses = 0, collisions = 0, wrong = 0, confidentlyWrong = 0;
};

Answers againstBruteForce(const TriangleMesh& mesh, const QuerySettings& settings) {
  const AdbTree tree(mesh);
  QueryScratch scratch;
  std::mt19937_64 rng(test::kSeed);
  Answers n;
  for (double dist = 0.3; dist <= 2.0; dist += 0.1) {
    for (int i = 0; i < 12; ++i) {
      const PosePair p = benchmarkPoses(mesh.bounds(), dist, rng);
      const QueryResult r = collide(tree, p.a, tree, p.b, settings, scratch);
      const bool truth = test::bruteForceCollide(mesh, p.a, mesh, p.b);
      ++n.poses;
      n.collisions += truth ? 1 : 0;
      if (r.collides == truth) continue;
      ++n.wrong;
      n.confidentlyWrong += r.confidence >= 0.9 ? 1 : 0;
    }
  }
  return n;
}

TEST(MeshesAsTheyCome, UnbudgetedAdbAnswersEveryLowPolyAndSliverPoseRight) {
  const TriangleMesh meshes[] = {gen::makeModel("pipes", 384), gen::makeCylinder(0.3, 2.0, 48, 1, 1)};
  for (const TriangleMesh& mesh : meshes) {
    const Answers n = againstBruteForce(mesh, test::adbSettings(0.99, 10));
    EXPECT_EQ(n.wrong, 0) << mesh.triangleCount() << " triangles, " << n.poses << " poses";
    EXPECT_GT(n.collisions, n.poses / 5);
    EXPECT_LT(n.collisions, n.poses * 19 / 20);
  }
}

TEST(MeshesAsTheyCome, ThePapersRulesAnswerLowPolyPipesWronglyAndConfidently) {
  // The contrast that shows the test above can fail: the same poses under the paper's rules.
  QuerySettings paper = test::adbSettings(0.99, 10);
  paper.pruneImprobable = true;
  paper.minTrianglesToAccept = 0;
  const Answers n = againstBruteForce(gen::makeModel("pipes", 384), paper);
  EXPECT_GT(n.confidentlyWrong, n.poses / 100) << n.wrong << " wrong of " << n.poses;
}


// A dense cylinder of 100:1 slivers (20k triangles, as CAD exports tessellate): every node has
// enough triangles to be accepted, but its slivers do not fill its cells as the model reads
// them. Measured before the sliver flag: 93 of 4,800 poses answered "collision" wrongly at
// 0.99 / 10, 40 with confidence >= 0.9. Oracle: exact mode (checked against the brute force
// on slivers by ExactMode.*Slivers*).
TEST(MeshesAsTheyCome, UnbudgetedAdbAnswersADenseSliverCylinderAsExactModeDoes) {
  const TriangleMesh mesh = gen::makeModel("slivers", 20000);
  const AdbTree tree(mesh);
  QueryScratch scratch;
  std::mt19937_64 rng(test::kSeed);
  int poses = 0, collisions = 0, wrong = 0, paperWrong = 0;
  QuerySettings paper = test::adbSettings(0.99, 10);
  paper.minTrianglesToAccept = 0;
  for (double dist = 0.4; dist <= 2.0; dist += 0.1) {
    for (int i = 0; i < 30; ++i) {
      const PosePair p = benchmarkPoses(mesh.bounds(), dist, rng);
      const bool truth = collide(tree, p.a, tree, p.b, test::exactSettings(), scratch).collides;
      ++poses;
      collisions += truth ? 1 : 0;
      wrong += collide(tree, p.a, tree, p.b, test::adbSettings(0.99, 10), scratch).collides != truth;
      paperWrong += collide(tree, p.a, tree, p.b, paper, scratch).collides != truth;
    }
  }
  EXPECT_EQ(wrong, 0) << "of " << poses;
  EXPECT_GT(paperWrong, 0) << "the poses must show what slivers do to the model";
  EXPECT_GT(collisions, poses / 5);
  EXPECT_LT(collisions, poses * 4 / 5);
}

}  // namespace
}  // namespace adb
