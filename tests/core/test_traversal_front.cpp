// Work carried across queries (QuerySettings::keepFront): a Traversal reset step after step
// for the same two trees walks the node pairs it evaluated last time instead of descending
// from the roots. The oracle is the descent from the roots (collide() with a fresh scratch):
// the walk must find the same witnesses in the same order, report that descent's cost as
// fromScratchNodePairs, and cost far less where the bodies rest.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>
#include <vector>

#include "adb/core/tree.h"
#include "adb/support/mesh_generators.h"
#include "test_support.h"

namespace adb {
namespace {

// What contact generation asks (plugin/bullet's mesh-mesh pairs): hits sampled per region,
// at most 64, stopping once they are held.
QuerySettings contactSettings(double margin = 0.0) {
  QuerySettings s = test::exactSettings();
  s.stopAtFirstHit = false;
  s.maxWitnesses = 64;
  s.hitsPerRegion = 4;
  s.regionDepth = 8;
  s.stopWhenWitnessesFull = true;
  s.contactMargin = margin;
  return s;
}

Pose rotated(const Vec3& axis, double angle, const Vec3& translation) {
  Pose p;
  p.rotation = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  p.translation = translation;
  return p;
}

void expectSameWitnesses(const std::vector<Witness>& walked, const std::vector<Witness>& fresh,
                         int step) {
  ASSERT_EQ(walked.size(), fresh.size()) << "step " << step;
  for (std::size_t i = 0; i < walked.size(); ++i) {
    EXPECT_EQ(std::tie(walked[i].nodeA, walked[i].nodeB, walked[i].triangleA, walked[i].triangleB),
              std::tie(fresh[i].nodeA, fresh[i].nodeB, fresh[i].triangleA, fresh[i].triangleB))
        << "step " << step << ", witness " << i;
    EXPECT_EQ(walked[i].distance, fresh[i].distance) << "step " << step << ", witness " << i;
  }
}

// Two interlocked tori: contact spread over two regions of each, thousands of node pairs.
struct FrontTori : ::testing::Test {
  TriangleMesh mesh = gen::makeTorus(1.0, 0.35, 48, 24);
  AdbTree tree{mesh};
  // B stands on A's tube, sunk 0.05 into it (tubes 0.35 thick): one contact region.
  Pose base = rotated(Vec3::UnitX(), M_PI / 2, Vec3(1.0, 0.0, 1.65));

  struct Totals {
    std::uint64_t walked = 0, fromScratch = 0;
    int collisions = 0;
  };

  // Runs the poses of B (A stays at the identity) with one Traversal keeping its front and,
  // for each, a descent from the roots; checks they agree step by step.
  Totals compare(const std::vector<Pose>& posesB, const QuerySettings& settings) {
    Traversal walk;
    QueryScratch scratch;
    QuerySettings keep = settings;
    keep.keepFront = true;
    Totals t;
    for (std::size_t i = 0; i < posesB.size(); ++i) {
      walk.reset(tree, Pose{}, tree, posesB[i], keep);
      const QueryResult w = walk.step();
      const QueryResult f = collide(tree, Pose{}, tree, posesB[i], settings, scratch);
      const int step = static_cast<int>(i);
      EXPECT_EQ(w.collides, f.collides) << "step " << step;
      EXPECT_EQ(w.stop, f.stop) << "step " << step;
      EXPECT_EQ(w.triangleTests, f.triangleTests) << "step " << step;
      EXPECT_EQ(w.fromScratchNodePairs, f.nodePairs) << "step " << step;
      EXPECT_EQ(w.witnessesDropped, f.witnessesDropped) << "step " << step;
      expectSameWitnesses(walk.witnesses(), scratch.witnesses(), step);
      if (i > 0) {  // the first query has no front: it descends from the roots
        t.walked += w.nodePairs;
        t.fromScratch += f.nodePairs;
      }
      t.collisions += f.collides ? 1 : 0;
    }
    return t;
  }
};

// A resting contact: B jitters by 1e-6 of its size around one pose, as a body on a pile does
// before Bullet puts it to sleep.
TEST_F(FrontTori, RestingContactWalksAQuarterOfTheDescentWithTheSameWitnesses) {
  std::mt19937_64 rng(test::kSeed);
  std::normal_distribution<double> jitter(0.0, 1e-6);
  std::vector<Pose> poses;
  for (int i = 0; i < 40; ++i) {
    const Vec3 axis(1.0 + jitter(rng), jitter(rng), jitter(rng));
    poses.push_back(rotated(axis, M_PI / 2 + jitter(rng),
                            base.translation + Vec3(jitter(rng), jitter(rng), jitter(rng))));
  }
  const Totals t = compare(poses, contactSettings());
  EXPECT_EQ(t.collisions, 40);
  ASSERT_GT(t.fromScratch, 0u);
  // Measured 0.06 (946 of 16,133): only the pairs whose certificates the jitter has used up
  // are tested again.
  EXPECT_LE(t.walked * 4, t.fromScratch) << t.walked << " walked of " << t.fromScratch;
}

// A body passing through the other, turning: fronts grow, shrink, are dropped and
// re-based; every step must still match the descent from the roots.
TEST_F(FrontTori, MovingBodiesFindWhatADescentFromTheRootsFinds) {
  for (const double margin : {0.0, 0.02}) {
    std::vector<Pose> poses;
    for (int i = 0; i <= 60; ++i) {
      const double s = i / 60.0;
      poses.push_back(rotated(Vec3(1.0, 0.3 * s, 0.1), M_PI / 2 + 0.8 * s,
                              Vec3(3.2 - 4.4 * s, 0.1 * s, 0.05 + 0.2 * s)));
    }
    const Totals t = compare(poses, contactSettings(margin));
    EXPECT_GT(t.collisions, 20) << "margin " << margin;
    EXPECT_LT(t.collisions, 61) << "margin " << margin;
    EXPECT_LT(t.walked, t.fromScratch) << "margin " << margin;
  }
}

// A query cut by a node-pair budget and resumed, or abandoned for the next pose with its
// walk unfinished: once a walk completes it has found every hit a descent from the roots
// finds (regions off, so the set does not depend on the order).
TEST_F(FrontTori, CutWalksResumeAndUnfinishedOnesAreKept) {
  QuerySettings settings = test::collectEverySettings();
  QuerySettings keep = settings;
  keep.keepFront = true;
  Traversal walk;
  QueryScratch scratch;
  int completedAfterCuts = 0;
  for (int i = 0; i <= 30; ++i) {
    const double s = i / 30.0;
    const Pose pose = rotated(Vec3(1.0, 0.2 * s, 0.0), M_PI / 2 + 0.3 * s,
                              Vec3(1.3 - 0.6 * s, 0.0, 0.05));
    walk.reset(tree, Pose{}, tree, pose, keep);
    int steps = 0;
    while (!walk.done() && steps < (i % 3 == 2 ? 2 : 100000)) {
      const QueryResult& r = walk.step(StepBudget{40, std::numeric_limits<double>::infinity()});
      EXPECT_GE(r.confidence, 0.0);
      EXPECT_LE(r.confidence, 1.0);
      if (!walk.done()) {
        EXPECT_FALSE(walk.openPairs().empty()) << "a cut walk shows what it has left";
      }
      ++steps;
    }
    if (!walk.done()) continue;  // abandoned: the next reset keeps what it recorded
    collide(tree, Pose{}, tree, pose, settings, scratch);
    auto sorted = [](const std::vector<Witness>& ws) {
      std::vector<std::tuple<std::uint32_t, std::uint32_t>> out;
      for (const Witness& w : ws) out.emplace_back(w.triangleA, w.triangleB);
      std::sort(out.begin(), out.end());
      return out;
    };
    EXPECT_EQ(sorted(walk.witnesses()), sorted(scratch.witnesses())) << "pose " << i;
    if (steps > 1) ++completedAfterCuts;
  }
  EXPECT_GT(completedAfterCuts, 10);
}

// Another pair of trees, or another margin, makes the front useless: it is dropped, and the
// answer is still the descent's.
TEST_F(FrontTori, AnotherTreeOrMarginStartsAfresh) {
  const TriangleMesh other = gen::makeTorus(1.0, 0.3, 40, 20);
  const AdbTree otherTree(other);
  Traversal walk;
  QueryScratch scratch;
  QuerySettings keep = contactSettings();
  keep.keepFront = true;
  walk.reset(tree, Pose{}, tree, base, keep);
  walk.step();
  walk.reset(tree, Pose{}, otherTree, base, keep);
  const QueryResult w = walk.step();
  const QueryResult f = collide(tree, Pose{}, otherTree, base, contactSettings(), scratch);
  EXPECT_EQ(w.nodePairs, f.nodePairs);  // nothing carried over: the whole descent
  expectSameWitnesses(walk.witnesses(), scratch.witnesses(), 0);
  keep.contactMargin = 0.01;
  walk.reset(tree, Pose{}, otherTree, base, keep);
  const QueryResult m = walk.step();
  EXPECT_EQ(m.nodePairs, m.fromScratchNodePairs);
}

}  // namespace
}  // namespace adb
