// The baselines that show whether ADB's probability pays for itself, end to end through the
// tool on a small knot run: root-boxes answers the root-box test, box-first without a
// binding budget is exact and with a zero budget is root-boxes, exact-cut without a binding
// budget is exact, adb-work:N respects its work budget and replays through the library,
// and reliability.csv and the summary's ece agree with the answers in queries.csv.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "adb/support/mesh_generators.h"
#include "adb/core/query.h"
#include "adb/core/tree.h"
#include "root_overlap.h"
#include "tool_run.h"

namespace adb::tradeoff::test {
namespace {

// Distances from deep overlap to root boxes apart. Budgets: 0 cuts everything; 1 s never
// binds on a 2000-triangle knot (queries take microseconds); 10^8 node pairs never bind
// either.
const std::vector<std::string> kRunArgs{
    "--model", "knot:2000", "--rotations", "6", "--distances", "0.3:2.8:0.5", "--methods",
    "adb,exact,exact-cut,box-first,root-boxes", "--p-min", "0.9", "--k-min", "1",
    "--budget-us", "none,0,1000000", "--budget-pairs", "50,100000000", "--repeats", "1",
    "--no-plots"};
constexpr int kPoses = 6 * 6;

Pose poseOf(const CsvTable& t, std::size_t row, const std::string& p) {
  const Eigen::Quaterniond q(std::stod(t.at(row, p + "_qw")), std::stod(t.at(row, p + "_qx")),
                             std::stod(t.at(row, p + "_qy")), std::stod(t.at(row, p + "_qz")));
  return Pose::fromQuaternion(q, Vec3(std::stod(t.at(row, p + "_tx")),
                                      std::stod(t.at(row, p + "_ty")),
                                      std::stod(t.at(row, p + "_tz"))));
}

std::string settingKey(const CsvTable& t, std::size_t row) {
  return t.at(row, "method") + "/" + t.at(row, "budget_us");
}

class PeerMethods : public ::testing::Test {
 protected:
  void SetUp() override {
    m_dir = freshDir(std::string("peer_methods_") +
                     ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::vector<std::string> args = kRunArgs;
    args.insert(args.end(), {"--out", m_dir});
    const RunResult r = runTool(args);
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
    m_q = readCsv(m_dir + "/queries.csv");
    // Rows by pose (distance, rotation) and setting (method, budget).
    for (std::size_t i = 0; i < m_q.rows.size(); ++i) {
      m_rows[{m_q.at(i, "distance"), m_q.at(i, "rotation")}][settingKey(m_q, i)] = i;
    }
  }
  std::string m_dir;
  CsvTable m_q;
  std::map<std::pair<std::string, std::string>, std::map<std::string, std::size_t>> m_rows;
};

TEST_F(PeerMethods, BaselinesAnswerAsSpecifiedOnEveryPose) {
  ASSERT_EQ(m_rows.size(), static_cast<std::size_t>(kPoses));
  const Aabb bounds = gen::makeModel("knot", 2000).bounds();
  int hits = 0, overlapping = 0;
  for (const auto& [pose, bySetting] : m_rows) {
    // 3 adb, 2 adb-work, exact, 2 exact-cut, 2 box-first, root-boxes
    ASSERT_EQ(bySetting.size(), 11u);
    const auto collides = [&](const std::string& key) {
      return m_q.at(bySetting.at(key), "collides");
    };
    const auto confidence = [&](const std::string& key) {
      return std::stod(m_q.at(bySetting.at(key), "confidence"));
    };
    const std::size_t any = bySetting.begin()->second;
    const bool roots = rootBoxesOverlap(bounds, poseOf(m_q, any, "a"), poseOf(m_q, any, "b"));
    const std::string where = "distance " + pose.first + " rotation " + pose.second;
    EXPECT_EQ(collides("root-boxes/"), roots ? "1" : "0") << where;
    EXPECT_EQ(confidence("root-boxes/"), 0.5) << where;
    EXPECT_EQ(collides("box-first/0"), collides("root-boxes/")) << where;
    EXPECT_EQ(collides("box-first/1000000"), collides("exact/")) << where;
    EXPECT_EQ(confidence("box-first/1000000"), 1.0) << where;
    EXPECT_EQ(collides("exact-cut/1000000"), collides("exact/")) << where;
    EXPECT_EQ(confidence("exact-cut/1000000"), 1.0) << where;
    if (collides("exact/") == "1") {
      EXPECT_EQ(collides("root-boxes/"), "1") << where << ": a hit needs overlapping roots";
    }
    // A zero budget cuts exact mode before it tests a triangle: it answers "no", with the
    // estimate's 1 - P(collision) as its confidence where the roots overlap (where they are
    // apart it is decided, and certain).
    EXPECT_EQ(collides("exact-cut/0"), "0") << where;
    if (roots) {
      EXPECT_LT(confidence("exact-cut/0"), 1.0) << where;
    }
    // A work budget that never binds changes nothing.
    const std::size_t work = bySetting.at("adb-work:100000000/");
    const std::size_t unbudgeted = bySetting.at("adb/");
    EXPECT_EQ(m_q.at(work, "collides"), m_q.at(unbudgeted, "collides")) << where;
    EXPECT_EQ(m_q.at(work, "node_pairs"), m_q.at(unbudgeted, "node_pairs")) << where;
    EXPECT_LE(std::stoll(m_q.at(bySetting.at("adb-work:50/"), "node_pairs")), 50) << where;
    hits += collides("exact/") == "1" ? 1 : 0;
    overlapping += roots ? 1 : 0;
  }
  EXPECT_GT(hits, 5);
  EXPECT_LT(hits, overlapping);  // root-boxes is wrong somewhere: the baseline is a baseline
  EXPECT_LT(overlapping, kPoses);
}

TEST_F(PeerMethods, WorkBudgetAnswersReplayThroughTheLibrary) {
  const TriangleMesh mesh = gen::makeModel("knot", 2000);
  const AdbTree tree(mesh);
  QueryScratch scratch;
  int replayed = 0, cut = 0;
  for (std::size_t i = 0; i < m_q.rows.size(); ++i) {
    if (m_q.at(i, "method") != "adb-work:50") continue;
    EXPECT_EQ(m_q.at(i, "p_min"), "0.9");
    EXPECT_EQ(m_q.at(i, "k_min"), "1");
    EXPECT_EQ(m_q.at(i, "budget_us"), "");
    QuerySettings s;
    s.pMin = 0.9;
    s.kMin = 1;
    s.budgetNodePairs = 50;
    const QueryResult r = collide(tree, poseOf(m_q, i, "a"), tree, poseOf(m_q, i, "b"), s, scratch);
    EXPECT_EQ(r.collides ? "1" : "0", m_q.at(i, "collides")) << "row " << i;
    EXPECT_EQ(std::to_string(r.nodePairs), m_q.at(i, "node_pairs")) << "row " << i;
    ++replayed;
    cut += r.stop == StopReason::WorkBudget ? 1 : 0;
  }
  EXPECT_EQ(replayed, kPoses);
  EXPECT_GT(cut, 0);  // the budget binds somewhere: the runs differ from unbudgeted ones
}

// Per setting, the reliability bins recomputed from queries.csv (root boxes from the poses,
// reference = exact mode).
struct Recomputed {
  std::array<int, 10> count{};
  std::array<double, 10> confidence{}, right{};
  bool nearEdge = false;  // a printed confidence within 1e-8 of an edge may bin either way
};

TEST_F(PeerMethods, ReliabilityAndEceAgreeWithTheAnswers) {
  const Aabb bounds = gen::makeModel("knot", 2000).bounds();
  std::map<std::string, Recomputed> bySetting;  // method/p_min/k_min/budget_us
  for (const auto& [pose, rows] : m_rows) {
    const std::size_t any = rows.begin()->second;
    if (!rootBoxesOverlap(bounds, poseOf(m_q, any, "a"), poseOf(m_q, any, "b"))) continue;
    const std::string reference = m_q.at(rows.at("exact/"), "collides");
    for (const auto& [setting, i] : rows) {
      const std::string method = m_q.at(i, "method");
      if (method != "adb" && method.rfind("adb-work:", 0) != 0 && method != "exact-cut") continue;
      const double c = std::stod(m_q.at(i, "confidence"));
      const int bin = std::min(9, static_cast<int>(std::floor(c * 10.0)));
      const bool right = m_q.at(i, "collides") == reference;
      const bool nearEdge = std::abs(c * 10.0 - std::round(c * 10.0)) < 1e-7 && c > 0.0 && c < 1.0;
      const std::string key = method + "/" + m_q.at(i, "p_min") + "/" + m_q.at(i, "k_min") + "/" +
                              m_q.at(i, "budget_us");
      for (const std::string& k : {key, method == "exact-cut" ? std::string() : "adb-pooled///"}) {
        if (k.empty()) continue;
        Recomputed& r = bySetting[k];
        ++r.count[static_cast<std::size_t>(bin)];
        r.confidence[static_cast<std::size_t>(bin)] += c;
        r.right[static_cast<std::size_t>(bin)] += right ? 1.0 : 0.0;
        r.nearEdge = r.nearEdge || nearEdge;
      }
    }
  }
  ASSERT_EQ(bySetting.size(), 3u + 2u + 2u + 1u);
  const CsvTable rel = readCsv(m_dir + "/reliability.csv");
  ASSERT_EQ(rel.rows.size(), bySetting.size() * 10);
  std::map<std::string, double> ece;  // from reliability.csv's own rows
  std::map<std::string, int> total;
  for (std::size_t i = 0; i < rel.rows.size(); ++i) {
    const std::string key = rel.at(i, "method") + "/" + rel.at(i, "p_min") + "/" +
                            rel.at(i, "k_min") + "/" + rel.at(i, "budget_us");
    ASSERT_EQ(bySetting.count(key), 1u) << key;
    const Recomputed& r = bySetting[key];
    const auto b = static_cast<std::size_t>(std::stoi(rel.at(i, "bin")));
    const int count = std::stoi(rel.at(i, "count"));
    total[key] += count;
    if (r.nearEdge) continue;  // only the total can be compared for this setting
    ASSERT_EQ(count, r.count[b]) << key << " bin " << b;
    if (count == 0) {
      EXPECT_EQ(rel.at(i, "mean_confidence"), "") << key << " bin " << b;
      continue;
    }
    const double mc = std::stod(rel.at(i, "mean_confidence"));
    const double fr = std::stod(rel.at(i, "fraction_right"));
    EXPECT_NEAR(mc, r.confidence[b] / count, 1e-5) << key << " bin " << b;
    EXPECT_NEAR(fr, r.right[b] / count, 1e-5) << key << " bin " << b;
    ece[key] += count * std::abs(fr - mc);
  }
  const CsvTable s = readCsv(m_dir + "/summary.csv");
  int eceRows = 0;
  for (std::size_t i = 0; i < s.rows.size(); ++i) {
    const std::string key = s.at(i, "method") + "/" + s.at(i, "p_min") + "/" + s.at(i, "k_min") +
                            "/" + s.at(i, "budget_us");
    if (bySetting.count(key) == 0) {
      EXPECT_EQ(s.at(i, "ece"), "") << key << ": no estimate, no calibration";
      continue;
    }
    EXPECT_EQ(total[key], std::stoi(s.at(i, "overlapping"))) << key;
    if (bySetting[key].nearEdge) continue;
    EXPECT_NEAR(std::stod(s.at(i, "ece")), ece[key] / total[key], 1e-5) << key;
    ++eceRows;
  }
  EXPECT_GE(eceRows, 6);  // nearly every setting was compared
}

}  // namespace
}  // namespace adb::tradeoff::test
