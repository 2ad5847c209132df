// Pairs of different models through the built tool: every method answers every query of a
// pair, the rows name the pair "A+B" with both models' triangles, the distances are in the
// pair's unit, --poses inside puts B's box centre in A's box with A at the identity, and the
// poses of queries.csv reproduce the exact answers through the library on the two trees.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "adb/core/query.h"
#include "adb/core/tree.h"
#include "adb/support/benchmark_poses.h"
#include "adb/support/mesh_generators.h"
#include "tool_run.h"

namespace adb::tradeoff::test {
namespace {

Pose poseOf(const CsvTable& t, std::size_t row, const std::string& p) {
  const Eigen::Quaterniond q(std::stod(t.at(row, p + "_qw")), std::stod(t.at(row, p + "_qx")),
                             std::stod(t.at(row, p + "_qy")), std::stod(t.at(row, p + "_qz")));
  return Pose::fromQuaternion(q, Vec3(std::stod(t.at(row, p + "_tx")),
                                      std::stod(t.at(row, p + "_ty")),
                                      std::stod(t.at(row, p + "_tz"))));
}

std::string testDir() {
  return freshDir(std::string("pairs_") +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
}

// Every method and setting: 3 adb (none, 0 and 10^6 us), exact, gimpact, fcl, 2 exact-cut,
// 2 box-first, root-boxes. A budget of 10^6 us never binds; 0 cuts everything.
TEST(Pairs, EveryMethodAnswersEveryQueryOfAPair) {
  const std::string dir = testDir();
  const RunResult run = runTool(
      {"--model", "knot:2000", "--against-model", "gears:1000", "--rotations", "4",
       "--distances", "0.3:1.8:0.5", "--methods",
       "adb,exact,gimpact,fcl,exact-cut,box-first,root-boxes", "--p-min", "0.9", "--k-min", "1",
       "--budget-us", "none,0,1000000", "--repeats", "1", "--no-plots", "--out", dir});
  ASSERT_EQ(run.exitCode, 0) << run.stderrText;
  const CsvTable q = readCsv(dir + "/queries.csv");
  const std::size_t triangles =
      gen::makeModel("knot", 2000).triangleCount() + gen::makeModel("gears", 1000).triangleCount();
  constexpr std::size_t kPoses = 4 * 4, kSettings = 11;
  ASSERT_EQ(q.rows.size(), kPoses * kSettings);
  std::map<std::pair<std::string, std::string>, std::set<std::string>> settingsByPose;
  std::map<std::string, int> hitsByMethod;
  for (std::size_t i = 0; i < q.rows.size(); ++i) {
    EXPECT_EQ(q.at(i, "model"), "knot+gears") << "row " << i;
    EXPECT_EQ(q.at(i, "triangles"), std::to_string(triangles)) << "row " << i;
    const std::string collides = q.at(i, "collides");
    EXPECT_TRUE(collides == "0" || collides == "1") << "row " << i;
    const double confidence = std::stod(q.at(i, "confidence"));
    EXPECT_GE(confidence, 0.0) << "row " << i;
    EXPECT_LE(confidence, 1.0) << "row " << i;
    EXPECT_GE(std::stoll(q.at(i, "time_ns")), 0) << "row " << i;
    settingsByPose[{q.at(i, "distance"), q.at(i, "rotation")}].insert(
        q.at(i, "method") + "/" + q.at(i, "budget_us"));
    hitsByMethod[q.at(i, "method")] += collides == "1" ? 1 : 0;
  }
  ASSERT_EQ(settingsByPose.size(), kPoses);
  for (const auto& [pose, settings] : settingsByPose) {
    EXPECT_EQ(settings.size(), kSettings)
        << "distance " << pose.first << " rotation " << pose.second;
  }
  // The exact peers see collisions: the pair is really queried.
  EXPECT_GT(hitsByMethod["exact"], 0);
  EXPECT_EQ(hitsByMethod["exact"], hitsByMethod["fcl"]);

  const CsvTable s = readCsv(dir + "/summary.csv");
  ASSERT_EQ(s.rows.size(), kSettings + 1);  // and adb-pooled
  for (std::size_t i = 0; i < s.rows.size(); ++i) {
    EXPECT_EQ(s.at(i, "model"), "knot+gears");
    EXPECT_EQ(s.at(i, "queries"), s.at(i, "method") == "adb-pooled" ? "48" : "16");
  }
  const CsvTable cells = readCsv(dir + "/cells.csv");
  EXPECT_EQ(cells.rows.size(), 512u);  // one histogram for the pair: both trees'
}

// Zachmann's poses for a pair: each model rotated about its own box centre, the centres
// `distance` pair units apart (the mean of the two models' units).
TEST(Pairs, DistancesAreInThePairsUnit) {
  const std::string dir = testDir();
  const RunResult run = runTool({"--model", "slivers:2000", "--against-model", "robot",
                                 "--rotations", "3", "--distances", "0.5,1.5", "--methods",
                                 "exact", "--repeats", "1", "--no-plots", "--out", dir});
  ASSERT_EQ(run.exitCode, 0) << run.stderrText;
  const CsvTable q = readCsv(dir + "/queries.csv");
  ASSERT_EQ(q.rows.size(), 6u);
  const Aabb a = gen::makeModel("slivers", 2000).bounds();
  const Aabb b = gen::makeFixedModel("robot").bounds();
  const double unit = 0.5 * (benchmarkUnit(a) + benchmarkUnit(b));
  EXPECT_NE(benchmarkUnit(a), benchmarkUnit(b));  // the mean is not one model's unit
  for (std::size_t i = 0; i < q.rows.size(); ++i) {
    EXPECT_EQ(q.at(i, "model"), "slivers+robot");
    const Vec3 ca = poseOf(q, i, "a").apply(a.center());
    const Vec3 cb = poseOf(q, i, "b").apply(b.center());
    EXPECT_NEAR((cb - ca).norm() / unit, std::stod(q.at(i, "distance")), 1e-9) << "row " << i;
  }
}

// FCL's robot in a room: the room fixed at the identity, the robot's box centre uniformly
// random in the room's box (it reaches every part of it), the distance column the centres'
// distance rounded to 0.1 unit.
TEST(Pairs, InsidePosesPutBsCentreInAsBox) {
  const std::string dir = testDir();
  const RunResult run = runTool({"--model", "room", "--against-model", "robot", "--poses",
                                 "inside", "--rotations", "200", "--methods", "exact",
                                 "--repeats", "1", "--no-plots", "--out", dir});
  ASSERT_EQ(run.exitCode, 0) << run.stderrText;
  const CsvTable q = readCsv(dir + "/queries.csv");
  ASSERT_EQ(q.rows.size(), 200u);
  const Aabb room = gen::makeFixedModel("room").bounds();
  const Aabb robot = gen::makeFixedModel("robot").bounds();
  const double unit = benchmarkUnit(room, robot);
  Vec3 lo = Vec3::Constant(1e300), hi = -lo;
  int hits = 0;
  std::set<std::string> rotations;
  for (std::size_t i = 0; i < q.rows.size(); ++i) {
    for (const char* field : {"a_qx", "a_qy", "a_qz", "a_tx", "a_ty", "a_tz"}) {
      EXPECT_EQ(q.at(i, field), "0") << "row " << i << " " << field;
    }
    EXPECT_EQ(q.at(i, "a_qw"), "1") << "row " << i;
    const Vec3 centre = poseOf(q, i, "b").apply(robot.center());
    EXPECT_TRUE((centre.array() >= room.lo.array() - 1e-12).all() &&
                (centre.array() <= room.hi.array() + 1e-12).all())
        << "row " << i << ": " << centre.transpose();
    lo = lo.cwiseMin(centre);
    hi = hi.cwiseMax(centre);
    const double distance = std::stod(q.at(i, "distance"));
    EXPECT_NEAR(distance, (centre - room.center()).norm() / unit, 0.05 + 1e-9) << "row " << i;
    EXPECT_NEAR(distance * 10.0, std::round(distance * 10.0), 1e-9) << "row " << i;
    rotations.insert(q.at(i, "rotation"));
    hits += q.at(i, "collides") == "1" ? 1 : 0;
  }
  EXPECT_EQ(rotations.size(), 200u);  // the rotation column numbers the poses
  // Uniform over the box: 200 centres reach within a tenth of every face.
  EXPECT_TRUE(((lo - room.lo).array() < 0.1 * room.extent().array()).all()) << lo.transpose();
  EXPECT_TRUE(((room.hi - hi).array() < 0.1 * room.extent().array()).all()) << hi.transpose();
  // The robot meets the walls and the furniture sometimes, not always.
  EXPECT_GT(hits, 10);
  EXPECT_LT(hits, 190);
}

// The pair's poses in queries.csv reproduce the exact answers through the library: tree A of
// the first model at pose a, tree B of the second at pose b.
TEST(Pairs, CsvPosesReproduceExactAnswersOnTheTwoTrees) {
  const std::string dir = testDir();
  const RunResult run = runTool({"--model", "room", "--against-model", "robot", "--poses",
                                 "inside", "--rotations", "60", "--methods", "exact,adb",
                                 "--p-min", "0.9", "--k-min", "1", "--budget-us", "none",
                                 "--repeats", "1", "--no-plots", "--out", dir});
  ASSERT_EQ(run.exitCode, 0) << run.stderrText;
  const CsvTable q = readCsv(dir + "/queries.csv");
  const AdbTree room(gen::makeFixedModel("room"));
  const AdbTree robot(gen::makeFixedModel("robot"));
  QueryScratch scratch;
  int replayed = 0;
  for (std::size_t i = 0; i < q.rows.size(); ++i) {
    QuerySettings s;
    if (q.at(i, "method") == "exact") {
      s.mode = QueryMode::Exact;
    } else {
      s.pMin = 0.9;
      s.kMin = 1;
    }
    const QueryResult r = collide(room, poseOf(q, i, "a"), robot, poseOf(q, i, "b"), s, scratch);
    EXPECT_EQ(r.collides ? "1" : "0", q.at(i, "collides")) << "row " << i;
    EXPECT_EQ(std::to_string(r.nodePairs), q.at(i, "node_pairs")) << "row " << i;
    ++replayed;
  }
  EXPECT_EQ(replayed, 120);
}

}  // namespace
}  // namespace adb::tradeoff::test
