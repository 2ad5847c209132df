// adb-tradeoff's files have exactly the documented columns (docs/benchmark.md and
// the tool's issue), a row for every query of every method, a summary that agrees with the
// rows it summarises, and reliability.csv's 10 bins per estimating method setting; a second
// run adds the baselines (exact-cut, box-first, root-boxes) and the work budgets.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <vector>

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
    "error_pct,ece,mean_confidence,mean_node_pairs,speedup_vs_exact,speedup_vs_gimpact,"
    "speedup_vs_fcl";
const char* const kCellsHeader = "model,triangles,cell,count";
const char* const kReliabilityHeader =
    "model,triangles,method,p_min,k_min,budget_us,bin,bin_lo,bin_hi,count,mean_confidence,"
    "fraction_right";
const char* const kPooledKey = "adb-pooled///";

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
  ASSERT_EQ(s.rows.size(), static_cast<std::size_t>(kMethods + 1));  // + adb-pooled
  // Mean time per method recomputed from queries.csv.
  const CsvTable q = readCsv(m_dir + "/queries.csv");
  std::map<std::string, double> sumNs;
  for (std::size_t i = 0; i < q.rows.size(); ++i) sumNs[methodKey(q, i)] += std::stod(q.at(i, "time_ns"));
  std::map<std::string, double> meanUs;
  double adbSumNs = 0.0;
  for (std::size_t i = 0; i < s.rows.size(); ++i) {
    ASSERT_EQ(s.rows[i].size(), s.header.size());
    const std::string key = methodKey(s, i);
    if (key == kPooledKey) continue;  // checked below
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
    // Only ADB estimates its confidence: the others have no calibration error.
    EXPECT_EQ(s.at(i, "ece").empty(), method != "adb") << key;
    if (method == "adb") {
      const double ece = std::stod(s.at(i, "ece"));
      EXPECT_GE(ece, 0.0) << key;
      EXPECT_LE(ece, 1.0) << key;
      adbSumNs += sumNs[key];
    }
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
    if (methodKey(s, i) == kPooledKey) continue;
    const double own = meanUs[methodKey(s, i)];
    EXPECT_NEAR(std::stod(s.at(i, "speedup_vs_exact")), meanUs["exact///"] / own,
                1e-3 * meanUs["exact///"] / own);
    EXPECT_NEAR(std::stod(s.at(i, "speedup_vs_fcl")), meanUs["fcl///"] / own,
                1e-3 * meanUs["fcl///"] / own);
  }
  // adb-pooled, the last row: the four ADB settings' queries together.
  const std::size_t pooled = s.rows.size() - 1;
  ASSERT_EQ(methodKey(s, pooled), kPooledKey);
  EXPECT_EQ(s.at(pooled, "queries"), std::to_string(kAdbSettings * kDistances * kRotations));
  EXPECT_EQ(std::stoi(s.at(pooled, "overlapping")),
            kAdbSettings * std::stoi(s.at(0, "overlapping")));
  const double pooledMean = std::stod(s.at(pooled, "mean_us"));
  EXPECT_NEAR(pooledMean, adbSumNs / (kAdbSettings * kDistances * kRotations) / 1000.0,
              1e-3 * pooledMean + 1e-3);
  EXPECT_FALSE(s.at(pooled, "error_pct").empty());
  EXPECT_FALSE(s.at(pooled, "ece").empty());
}

TEST_F(OutputFormat, ReliabilityCsvHasTenBinsPerAdbSettingAndAgreesWithTheSummary) {
  const CsvTable r = readCsv(m_dir + "/reliability.csv");
  EXPECT_EQ(r.headerLine, kReliabilityHeader);
  ASSERT_EQ(r.rows.size(), static_cast<std::size_t>((kAdbSettings + 1) * 10));  // + pooled
  const CsvTable s = readCsv(m_dir + "/summary.csv");
  std::map<std::string, std::size_t> summaryRow;
  for (std::size_t i = 0; i < s.rows.size(); ++i) summaryRow[methodKey(s, i)] = i;
  std::map<std::string, int> counted;
  std::map<std::string, double> weightedGap;  // sum of count * |fraction right - confidence|
  for (std::size_t i = 0; i < r.rows.size(); ++i) {
    ASSERT_EQ(r.rows[i].size(), r.header.size()) << "row " << i;
    const std::string key = methodKey(r, i);
    EXPECT_TRUE(r.at(i, "method") == "adb" || key == kPooledKey) << key;
    const int bin = std::stoi(r.at(i, "bin"));
    EXPECT_EQ(bin, static_cast<int>(i % 10)) << "row " << i;  // groups of 10, in bin order
    EXPECT_NEAR(std::stod(r.at(i, "bin_lo")), bin * 0.1, 1e-12);
    EXPECT_NEAR(std::stod(r.at(i, "bin_hi")), (bin + 1) * 0.1, 1e-12);
    const int count = std::stoi(r.at(i, "count"));
    counted[key] += count;
    EXPECT_EQ(r.at(i, "mean_confidence").empty(), count == 0) << key << " bin " << bin;
    EXPECT_EQ(r.at(i, "fraction_right").empty(), count == 0) << key << " bin " << bin;
    if (count == 0) continue;
    const double confidence = std::stod(r.at(i, "mean_confidence"));
    EXPECT_GE(confidence, bin * 0.1 - 1e-9) << key;  // a bin's mean lies in the bin
    EXPECT_LE(confidence, (bin + 1) * 0.1 + 1e-9) << key;
    weightedGap[key] += count * std::abs(std::stod(r.at(i, "fraction_right")) - confidence);
  }
  ASSERT_EQ(counted.size(), static_cast<std::size_t>(kAdbSettings + 1));
  for (const auto& [key, count] : counted) {
    ASSERT_EQ(summaryRow.count(key), 1u) << key;
    const std::size_t row = summaryRow[key];
    // Only queries whose root boxes overlap are counted, as for the error rate.
    EXPECT_EQ(count, std::stoi(s.at(row, "overlapping"))) << key;
    EXPECT_NEAR(std::stod(s.at(row, "ece")), weightedGap[key] / count, 1e-5) << key;
  }
}

TEST_F(OutputFormat, SummaryMarkdownNamesTheCommandAndEveryMethod) {
  std::ifstream in(m_dir + "/summary.md");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("--model knot:2000"), std::string::npos);
  EXPECT_NE(text.find("Machine:"), std::string::npos);
  for (const char* method : {"| adb |", "| exact |", "| gimpact |", "| fcl |", "| adb-pooled |"}) {
    EXPECT_NE(text.find(method), std::string::npos) << method;
  }
  EXPECT_NE(text.find("| error % | ece |"), std::string::npos);
  // The Budgets section: ADB's time-budget families, and ADB at exact mode's mean time.
  const std::size_t budgets = text.find("## Budgets");
  ASSERT_NE(budgets, std::string::npos);
  EXPECT_NE(text.find("### knot (", budgets), std::string::npos);
  EXPECT_NE(text.find("| adb (time budget) | 0.9 | 1 |", budgets), std::string::npos);
  EXPECT_NE(text.find("| adb (time budget) | 0.9 | 10 |", budgets), std::string::npos);
  EXPECT_NE(text.find("exact mode's mean query time", budgets), std::string::npos);
  EXPECT_EQ(text.find("nan", budgets), std::string::npos);
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

// The opt-in baselines and work budgets: ADB p_min 0.9, k_min 1 at budgets none and 20 us and
// at 40 and 400 node pairs, exact mode, exact-cut and box-first at 20 us, root-boxes.
class OutputFormatNewMethods : public OutputFormat {
 protected:
  void SetUp() override {
    m_dir = freshDir(std::string("output_format_new_") +
                     ::testing::UnitTest::GetInstance()->current_test_info()->name());
    const RunResult r = runTool({"--model", "knot:2000", "--rotations", "3", "--distances",
                                 "0.4:1.6:0.6", "--methods",
                                 "adb,exact,exact-cut,box-first,root-boxes", "--p-min", "0.9",
                                 "--k-min", "1", "--budget-us", "none,20", "--budget-pairs",
                                 "40,400", "--repeats", "1", "--no-plots", "--out", m_dir});
    ASSERT_EQ(r.exitCode, 0) << r.stderrText;
  }
};

// Method settings of the run, as method/p_min/k_min/budget_us, in the tool's order.
const std::vector<std::string> kNewRunSettings{
    "adb/0.9/1/",   "adb/0.9/1/20", "adb-work:40/0.9/1/", "adb-work:400/0.9/1/", "exact///",
    "exact-cut///20", "box-first///20", "root-boxes///"};

TEST_F(OutputFormatNewMethods, QueriesCsvKeepsItsHeaderAndFillsTheParameterColumnsPerMethod) {
  const CsvTable q = readCsv(m_dir + "/queries.csv");
  EXPECT_EQ(q.headerLine, kQueriesHeader);
  ASSERT_EQ(q.rows.size(), kNewRunSettings.size() * kDistances * kRotations);
  std::map<std::string, int> perSetting;
  for (std::size_t i = 0; i < q.rows.size(); ++i) {
    ASSERT_EQ(q.rows[i].size(), q.header.size()) << "row " << i;
    const std::string key = methodKey(q, i);
    ++perSetting[key];
    // Methods take turns pose by pose, in the tool's order.
    EXPECT_EQ(key, kNewRunSettings[i % kNewRunSettings.size()]) << "row " << i;
    const std::string& method = q.at(i, "method");
    const double confidence = std::stod(q.at(i, "confidence"));
    EXPECT_GE(confidence, 0.0) << key;
    EXPECT_LE(confidence, 1.0) << key;
    if (method == "exact") {
      EXPECT_EQ(confidence, 1.0);
    }
    if (method == "root-boxes") {
      EXPECT_EQ(confidence, 0.5);
    }
    if (method == "box-first") {
      EXPECT_TRUE(confidence == 1.0 || (confidence == 0.5 && q.at(i, "collides") == "1"))
          << "row " << i << ": exact when it completes, 'collides' at 0.5 when cut";
    }
    EXPECT_EQ(q.at(i, "node_pairs").empty(), method == "root-boxes") << key;
  }
  for (const std::string& key : kNewRunSettings) {
    EXPECT_EQ(perSetting[key], kDistances * kRotations) << key;
  }
}

TEST_F(OutputFormatNewMethods, SummaryAndReliabilityCoverExactlyTheEstimatingSettings) {
  const CsvTable s = readCsv(m_dir + "/summary.csv");
  EXPECT_EQ(s.headerLine, kSummaryHeader);
  ASSERT_EQ(s.rows.size(), kNewRunSettings.size() + 1);
  const std::set<std::string> estimating{"adb/0.9/1/", "adb/0.9/1/20", "adb-work:40/0.9/1/",
                                         "adb-work:400/0.9/1/", "exact-cut///20", kPooledKey};
  for (std::size_t i = 0; i < s.rows.size(); ++i) {
    const std::string key = methodKey(s, i);
    EXPECT_EQ(key, i < kNewRunSettings.size() ? kNewRunSettings[i] : kPooledKey);
    EXPECT_FALSE(s.at(i, "error_pct").empty()) << key;
    EXPECT_EQ(s.at(i, "ece").empty(), estimating.count(key) == 0) << key;
  }
  // adb-pooled holds the adb and adb-work settings (not exact-cut): 4 of them.
  EXPECT_EQ(s.at(s.rows.size() - 1, "queries"), std::to_string(4 * kDistances * kRotations));

  const CsvTable r = readCsv(m_dir + "/reliability.csv");
  EXPECT_EQ(r.headerLine, kReliabilityHeader);
  ASSERT_EQ(r.rows.size(), estimating.size() * 10);
  std::set<std::string> groups;
  for (std::size_t i = 0; i < r.rows.size(); ++i) groups.insert(methodKey(r, i));
  EXPECT_EQ(groups, estimating);

  std::ifstream in(m_dir + "/summary.md");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::size_t budgets = text.find("## Budgets");
  ASSERT_NE(budgets, std::string::npos);
  for (const char* family :
       {"| adb (time budget) | 0.9 | 1 |", "| adb-work (node pairs) | 0.9 | 1 |",
        "| exact-cut (time budget) |", "| box-first (time budget) |"}) {
    EXPECT_NE(text.find(family, budgets), std::string::npos) << family;
  }
}

}  // namespace
}  // namespace adb::tradeoff::test
