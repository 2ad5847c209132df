// The Budgets section of summary.md (budgets.h): the log-scale interpolation of the error
// between measured budgets, and the section's text for hand-made summary rows.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "budgets.h"

namespace adb::tradeoff {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kNone = std::numeric_limits<double>::infinity();

TEST(TradeoffBudgets, ErrorIsInterpolatedLinearlyInLogBudget) {
  const std::vector<BudgetPoint> points{{5.0, 40.0, 6.0}, {20.0, 10.0, 18.0}, {100.0, 0.0, 40.0}};
  double e = -1.0;
  ASSERT_TRUE(interpolateErrorPct(points, 20.0, e));
  EXPECT_DOUBLE_EQ(e, 10.0);  // a measured budget: its own error
  ASSERT_TRUE(interpolateErrorPct(points, 10.0, e));
  EXPECT_NEAR(e, 25.0, 1e-9);  // 10 is halfway from 5 to 20 in log: halfway from 40 to 10
  ASSERT_TRUE(interpolateErrorPct(points, std::sqrt(20.0 * 100.0), e));
  EXPECT_NEAR(e, 5.0, 1e-9);
  ASSERT_TRUE(interpolateErrorPct(points, 100.0, e));
  EXPECT_DOUBLE_EQ(e, 0.0);
  EXPECT_FALSE(interpolateErrorPct(points, 4.9, e));    // below the measured budgets
  EXPECT_FALSE(interpolateErrorPct(points, 100.1, e));  // above them
  EXPECT_FALSE(interpolateErrorPct({}, 10.0, e));
}

TEST(TradeoffBudgets, ZeroBudgetsAndMissingErrorsAreNotInterpolatedFrom) {
  // log(0) is -infinity: a budget of 0 cannot bracket anything on a log scale.
  const std::vector<BudgetPoint> points{{0.0, 100.0, 1.0}, {20.0, kNaN, 5.0}, {50.0, 8.0, 9.0},
                                        {100.0, 2.0, 20.0}};
  double e = -1.0;
  EXPECT_FALSE(interpolateErrorPct(points, 10.0, e));
  EXPECT_FALSE(interpolateErrorPct(points, 30.0, e));  // 20 has no error: range is 50..100
  ASSERT_TRUE(interpolateErrorPct(points, std::sqrt(50.0 * 100.0), e));
  EXPECT_NEAR(e, 5.0, 1e-9);
  EXPECT_FALSE(std::isnan(e));
}

SummaryRow row(const std::string& method, double pMin, int kMin, double budgetUs,
               std::uint64_t pairs, double errorPct, double meanUs) {
  SummaryRow r;
  r.model = "knot";
  r.triangles = 2000;
  r.method = method;
  r.params.hasQuality = method == "adb" || method.rfind("adb-work:", 0) == 0;
  r.params.pMin = pMin;
  r.params.kMin = kMin;
  r.params.budgetUs = budgetUs;
  r.params.budgetPairs = pairs;
  r.errorPct = errorPct;
  r.meanUs = meanUs;
  return r;
}

TEST(TradeoffBudgets, SectionNamesTheSmallestBudgetsReachingEachErrorLevel) {
  const double exactUs = std::sqrt(20.0 * 100.0);  // 44.7: halfway from 20 to 100 in log
  const std::vector<SummaryRow> rows{
      row("adb", 0.9, 1, kNone, 0, 0.0, 60.0),  // no budget: not a budget family point
      row("adb", 0.9, 1, 100.0, 0, 0.5, 30.0),  // rows out of budget order on purpose
      row("adb", 0.9, 1, 5.0, 0, 40.0, 5.5),
      row("adb", 0.9, 1, 20.0, 0, 4.0, 15.0),
      row("adb", 0.99, 10, 50.0, 0, 3.0, 40.0),
      row("adb", 0.99, 10, 100.0, 0, 0.0, 50.0),
      row("adb-work:100", 0.9, 1, kNone, 100, 10.0, 3.0),
      row("adb-work:1000", 0.9, 1, kNone, 1000, 0.8, 9.0),
      row("exact", 0, 0, kNone, 0, 0.0, exactUs),
      row("exact-cut", 0, 0, 20.0, 0, 50.0, 19.0),
      row("box-first", 0, 0, 20.0, 0, 60.0, 21.0),
      row("box-first", 0, 0, 100.0, 0, 3.0, 70.0),
  };
  const std::string text = budgetsSection({rows});
  EXPECT_NE(text.find("## Budgets"), std::string::npos) << text;
  EXPECT_NE(text.find("### knot (2000 triangles)"), std::string::npos) << text;
  EXPECT_NE(text.find("| adb (time budget) | 0.9 | 1 | 20 us (error 4.00 %, mean 15.0 us) | "
                      "100 us (error 0.50 %, mean 30.0 us) |"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("| adb (time budget) | 0.99 | 10 | 50 us (error 3.00 %, mean 40.0 us) | "
                      "100 us (error 0.00 %, mean 50.0 us) |"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("| adb-work (node pairs) | 0.9 | 1 | 1000 node pairs (error 0.80 %, "
                      "mean 9.0 us) | 1000 node pairs (error 0.80 %, mean 9.0 us) |"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("| exact-cut (time budget) |  |  | not reached | not reached |"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("| box-first (time budget) |  |  | 100 us (error 3.00 %, mean 70.0 us) | "
                      "not reached |"),
            std::string::npos)
      << text;
  // ADB at exact mode's mean time: 4 % at 20 us and 0.5 % at 100 us -> 2.25 % halfway.
  EXPECT_NE(text.find("exact mode's mean query time (44.7 us)"), std::string::npos) << text;
  EXPECT_NE(text.find("| 0.9 | 1 | 2.25 (interpolated between 20 and 100 us) |"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("| 0.99 | 10 | outside the measured budgets (50 to 100 us) |"),
            std::string::npos)
      << text;
}

TEST(TradeoffBudgets, WithoutAReferenceOrExactModeTheSectionSaysSo) {
  const std::vector<SummaryRow> rows{row("adb", 0.9, 1, 20.0, 0, kNaN, 15.0),
                                     row("adb", 0.9, 1, 100.0, 0, kNaN, 30.0)};
  const std::string text = budgetsSection({rows});
  EXPECT_NE(text.find("no reference"), std::string::npos) << text;
  EXPECT_NE(text.find("exact mode did not run"), std::string::npos) << text;
  EXPECT_EQ(text.find("nan"), std::string::npos) << text;
  const std::string none = budgetsSection({{row("fcl", 0, 0, kNone, 0, 0.0, 10.0)}});
  EXPECT_NE(none.find("No budgeted method ran."), std::string::npos) << none;
}

}  // namespace
}  // namespace adb::tradeoff
