// adb-tradeoff's files have exactly the documented columns (shared/design/BENCHMARK.md and
// the tool's issue), a row for every query of every method, and a summary that agrees with
// the rows it summarises.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <string>

#include "tool_run.h"

namespace adb::tradeoff::test {
namespace {

// Written out here, not taken from the tool: the test must catch a drifting header.
const char* const kQueriesHeader =
    "model,triangles,method,p_min,k_min,budget_us,distance,rotation,"
    "a_qw,a_qx,a_qy,a_qz,a_tx,a_ty,a_tz,b_qw,b_qx,b_qy,b_qz,b_tx,b_ty,b_tz,"
    "collides,confidence,time_ns,node_pairs";
const char* const kSummaryHeader =
    "model,triangles,method,p_min,k_min,budget_us,queries,overlapping,mean_us,p95_us,"
    "error_pct,mean_confidence,mean_node_pairs,speedup_vs_exact,speedup_vs_gimpact,"
    "speedup_vs_fcl";
const char* const kCellsHeader = "model,triangles,cell,count";

constexpr int kDistances = 3, kRotations = 3;
constexpr int kAdbSettings = 1 * 2 * 2;         // p_min 0.9 x k_min {1, 10} x budget {none, 20}
constexpr int kMethods = kAdbSettings + 3;      // + exact, gimpact, fcl

// One small run per test process, in a directory of its own: ctest runs each case as its own
// process, possibly in parallel.
class OutputFormat : public ::testing::Test {
 protected:
  void SetUp() override {
    m_dir = freshDir(std::string("output_format_") +
                     ::testing::UnitTest::GetInstance()->current_test_info()->name());
    const RunResult r = runTool({"--model", "knot:2000", "--rotations", "3", "--distances",
                                 "0.4:1.6:0.6", "--methods", "adb,exact,gimpact,fcl", "--p-min",
                                 "0.9", "--k-min", "1,10", "--budget-us", "none,20",
                                 "--repeats", "1", "--no-plots", "--out", m_dir});
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  }
  std::string m_dir;
};

std::string methodKey(const CsvTable& t, std::size_t row) {
  return t.at(row, "method") + "/" + t.at(row, "p_min") + "/" + t.at(row, "k_min") + "/" +
         t.at(row, "budget_us");
}

TEST_F(OutputFormat, QueriesCsvHasTheDocumentedColumnsAndEveryQueryOfEveryMethod) {
  const CsvTable q = readCsv(m_dir + "/queries.csv");
  EXPECT_EQ(q.headerLine, kQueriesHeader);
  ASSERT_EQ(q.rows.size(), static_cast<std::size_t>(kDistances * kRotations * kMethods));
  std::map<std::string, int> perMethod;
  for (std::size_t i = 0; i < q.rows.size(); ++i) {
    ASSERT_EQ(q.rows[i].size(), q.header.size()) << "row " << i;
    ++perMethod[methodKey(q, i)];
    const std::string& method = q.at(i, "method");
    const bool adb = method == "adb";
    EXPECT_EQ(q.at(i, "model"), "knot");
    EXPECT_EQ(q.at(i, "p_min").empty(), !adb) << "row " << i;
    EXPECT_EQ(q.at(i, "k_min").empty(), !adb) << "row " << i;
    if (!adb) {
      EXPECT_TRUE(q.at(i, "budget_us").empty());
    }
    EXPECT_TRUE(q.at(i, "collides") == "0" || q.at(i, "collides") == "1");
    const double confidence = std::stod(q.at(i, "confidence"));
    EXPECT_GE(confidence, 0.0);
    EXPECT_LE(confidence, 1.0);
    if (!adb) {
      EXPECT_EQ(confidence, 1.0) << method << " is exact";
    }
    EXPECT_GT(std::stod(q.at(i, "time_ns")), 0.0);
    const bool ownTree = adb || method == "exact";
    EXPECT_EQ(q.at(i, "node_pairs").empty(), !ownTree) << method;
    const int rotation = std::stoi(q.at(i, "rotation"));
    EXPECT_GE(rotation, 0);
    EXPECT_LT(rotation, kRotations);
  }
  // Every method: exact, gimpact, fcl and the four ADB settings, each on every pose.
  const std::set<std::string> expected{"adb/0.9/1/",  "adb/0.9/1/20", "adb/0.9/10/",
                                       "adb/0.9/10/20", "exact///",   "gimpact///",
                                       "fcl///"};
  std::set<std::string> seen;
  for (const auto& [key, count] : perMethod) {
    seen.insert(key);
    EXPECT_EQ(count, kDistances * kRotations) << key;
  }
  EXPECT_EQ(seen, expected);
}

TEST_F(OutputFormat, SummaryCsvHasTheDocumentedColumnsAndAgreesWithTheRows) {
  const CsvTable s = readCsv(m_dir + "/summary.csv");
  EXPECT_EQ(s.headerLine, kSummaryHeader);
  ASSERT_EQ(s.rows.size(), static_cast<std::size_t>(kMethods));
  // Mean time per method recomputed from queries.csv.
  const CsvTable q = readCsv(m_dir + "/queries.csv");
  std::map<std::string, double> sumNs;
  for (std::size_t i = 0; i < q.rows.size(); ++i) sumNs[methodKey(q, i)] += std::stod(q.at(i, "time_ns"));
  std::map<std::string, double> meanUs;
  for (std::size_t i = 0; i < s.rows.size(); ++i) {
    ASSERT_EQ(s.rows[i].size(), s.header.size());
    const std::string key = methodKey(s, i);
    EXPECT_EQ(s.at(i, "queries"), std::to_string(kDistances * kRotations)) << key;
    const double mean = std::stod(s.at(i, "mean_us"));
    EXPECT_NEAR(mean, sumNs[key] / (kDistances * kRotations) / 1000.0, 1e-3 * mean + 1e-3) << key;
    EXPECT_GE(std::stod(s.at(i, "p95_us")), 0.0);
    meanUs[key] = mean;
    const int overlapping = std::stoi(s.at(i, "overlapping"));
    EXPECT_GT(overlapping, 0);  // distance 0.4: the boxes always overlap
    EXPECT_LE(overlapping, kDistances * kRotations);
    EXPECT_FALSE(s.at(i, "error_pct").empty()) << key;  // exact ran: every row has a rate
    const std::string& method = s.at(i, "method");
    if (method == "exact") {
      EXPECT_EQ(std::stod(s.at(i, "error_pct")), 0.0);
    }
    EXPECT_EQ(s.at(i, "mean_node_pairs").empty(), method == "gimpact" || method == "fcl");
  }
  // Every exact collision needs overlapping root boxes: the filter cannot be tighter.
  int exactHits = 0;
  for (std::size_t i = 0; i < q.rows.size(); ++i) {
    exactHits += q.at(i, "method") == "exact" && q.at(i, "collides") == "1" ? 1 : 0;
  }
  EXPECT_GT(exactHits, 0);
  EXPECT_LE(exactHits, std::stoi(s.at(0, "overlapping")));
  // speedup_vs_X = X's mean / the row's mean.
  for (std::size_t i = 0; i < s.rows.size(); ++i) {
    const double own = meanUs[methodKey(s, i)];
    EXPECT_NEAR(std::stod(s.at(i, "speedup_vs_exact")), meanUs["exact///"] / own,
                1e-3 * meanUs["exact///"] / own);
    EXPECT_NEAR(std::stod(s.at(i, "speedup_vs_fcl")), meanUs["fcl///"] / own,
                1e-3 * meanUs["fcl///"] / own);
  }
}

TEST_F(OutputFormat, SummaryMarkdownNamesTheCommandAndEveryMethod) {
  std::ifstream in(m_dir + "/summary.md");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("--model knot:2000"), std::string::npos);
  EXPECT_NE(text.find("Machine:"), std::string::npos);
  for (const char* method : {"| adb |", "| exact |", "| gimpact |", "| fcl |"}) {
    EXPECT_NE(text.find(method), std::string::npos) << method;
  }
}

TEST_F(OutputFormat, CellsCsvHas512CellsPerModelWithSomeCounted) {
  const CsvTable c = readCsv(m_dir + "/cells.csv");
  EXPECT_EQ(c.headerLine, kCellsHeader);
  ASSERT_EQ(c.rows.size(), 512u);
  long long total = 0;
  for (std::size_t i = 0; i < c.rows.size(); ++i) {
    EXPECT_EQ(c.at(i, "model"), "knot");
    EXPECT_EQ(c.at(i, "cell"), std::to_string(i));
    total += std::stoll(c.at(i, "count"));
  }
  EXPECT_GT(total, 0);
}

}  // namespace
}  // namespace adb::tradeoff::test
