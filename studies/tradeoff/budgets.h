// The "Budgets" section of summary.md: what a budget buys, per model.
//
// For each budgeted method family (adb at each p_min x k_min under time budgets, adb-work at
// each p_min x k_min under work budgets, exact-cut, box-first): the smallest budget whose
// error rate is <= 5 % and the smallest whose error rate is <= 1 %, with the mean query time
// at that budget, or "not reached". Then ADB's error at a time budget equal to exact mode's
// mean query time, interpolated linearly in log(budget) between the two measured time
// budgets around it.
#pragma once

#include <string>
#include <vector>

#include "summary.h"

namespace adb::tradeoff {

/// Error-rate thresholds of the section, in percent.
inline constexpr double kLooseErrorPct = 5.0;
inline constexpr double kTightErrorPct = 1.0;

/// One measured budget of a family.
struct BudgetPoint {
  double budget = 0.0;    ///< microseconds or node pairs
  double errorPct = 0.0;  ///< NaN without a reference
  double meanUs = 0.0;
};

/// The error at `budget` interpolated linearly in log(budget) between the measured time
/// budgets around it (`points` sorted by budget; budgets <= 0 and NaN errors ignored).
/// Returns false when `budget` lies outside the measured positive budgets.
bool interpolateErrorPct(const std::vector<BudgetPoint>& points, double budget, double& errorPct);

/// The section (Markdown, starting with "## Budgets"), one part per model; `perModel` holds
/// each model's summary rows.
std::string budgetsSection(const std::vector<std::vector<SummaryRow>>& perModel);

}  // namespace adb::tradeoff
