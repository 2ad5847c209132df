// The "Budgets" section of summary.md (see budgets.h).
#include "budgets.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "csv_format.h"

namespace adb::tradeoff {
namespace {

// A budgeted method family of one model: one kind at one (p_min, k_min) where it has them.
struct Family {
  std::string kind;  // "adb", "adb-work", "exact-cut" or "box-first"
  MethodParams params;
  std::vector<BudgetPoint> points;  // sorted by budget once collected
};

bool isTimeBudgeted(const std::string& kind) { return kind != "adb-work"; }

// The family kind of a summary row; empty for rows without a budget.
std::string familyOf(const SummaryRow& r) {
  const bool timed = std::isfinite(r.params.budgetUs);
  if (r.method == "adb" && timed) return "adb";
  if (r.method.rfind("adb-work:", 0) == 0 && r.params.budgetPairs > 0) return "adb-work";
  if ((r.method == "exact-cut" || r.method == "box-first") && timed) return r.method;
  return "";
}

bool sameFamily(const Family& f, const std::string& kind, const MethodParams& p) {
  return f.kind == kind && (!p.hasQuality || (f.params.pMin == p.pMin && f.params.kMin == p.kMin));
}

std::vector<Family> familiesOf(const std::vector<SummaryRow>& rows) {
  std::vector<Family> families;  // in the order the rows first show them
  for (const SummaryRow& r : rows) {
    const std::string kind = familyOf(r);
    if (kind.empty()) continue;
    auto it = std::find_if(families.begin(), families.end(),
                           [&](const Family& f) { return sameFamily(f, kind, r.params); });
    if (it == families.end()) it = families.insert(families.end(), Family{kind, r.params, {}});
    const double budget = isTimeBudgeted(kind) ? r.params.budgetUs
                                               : static_cast<double>(r.params.budgetPairs);
    it->points.push_back(BudgetPoint{budget, r.errorPct, r.meanUs});
  }
  for (Family& f : families) {
    std::sort(f.points.begin(), f.points.end(),
              [](const BudgetPoint& x, const BudgetPoint& y) { return x.budget < y.budget; });
  }
  return families;
}

// A number for the text; "n/a" where there is none (a row without queries), never "nan".
std::string numberText(double v, const char* fmt) {
  return std::isfinite(v) ? format(fmt, v) : "n/a";
}

std::string budgetText(double budget, bool time) {
  return time ? format("%g us", budget) : format("%.0f node pairs", budget);
}

// The smallest budget of `f` whose error is at most `thresholdPct`, as a table cell.
std::string smallestReaching(const Family& f, double thresholdPct) {
  bool judged = false;
  for (const BudgetPoint& p : f.points) {
    if (std::isnan(p.errorPct)) continue;
    judged = true;
    if (p.errorPct <= thresholdPct) {
      return budgetText(p.budget, isTimeBudgeted(f.kind)) + " (error " +
             format("%.2f", p.errorPct) + " %, mean " + numberText(p.meanUs, "%.1f") + " us)";
    }
  }
  return judged ? "not reached" : "no reference (exact and fcl did not run)";
}

std::string familyLabel(const Family& f) {
  return f.kind == "adb" ? "adb (time budget)"
         : f.kind == "adb-work" ? "adb-work (node pairs)"
                                : f.kind + " (time budget)";
}

std::string thresholdTable(const std::vector<Family>& families) {
  std::string out = "| method | p_min | k_min | error <= " + format("%g", kLooseErrorPct) +
                    " % at | error <= " + format("%g", kTightErrorPct) + " % at |\n";
  out += "|---|---:|---:|---|---|\n";
  for (const Family& f : families) {
    const bool q = f.params.hasQuality;
    out += "| " + familyLabel(f) + " | " + (q ? format("%g", f.params.pMin) : "") + " | " +
           (q ? std::to_string(f.params.kMin) : "") + " | " + smallestReaching(f, kLooseErrorPct) +
           " | " + smallestReaching(f, kTightErrorPct) + " |\n";
  }
  return out;
}

// Budgets > 0 with an error rate: the points a log-scale interpolation can use.
std::vector<BudgetPoint> usable(const std::vector<BudgetPoint>& points) {
  std::vector<BudgetPoint> out;
  for (const BudgetPoint& p : points) {
    if (p.budget > 0.0 && std::isfinite(p.budget) && !std::isnan(p.errorPct)) out.push_back(p);
  }
  return out;
}

// Where a budget falls among usable points (sorted by budget): at point lo == hi, or strictly
// between points lo < hi; and the error there, interpolated linearly in log(budget).
struct Bracket {
  std::size_t lo = 0, hi = 0;
  double errorPct = 0.0;
};

// The bracket of `budget` among `points` (usable ones, sorted); false outside their range.
bool bracketOf(const std::vector<BudgetPoint>& points, double budget, Bracket& out) {
  if (points.empty() || !(budget >= points.front().budget) || !(budget <= points.back().budget)) {
    return false;
  }
  // The first point at or above the budget: the budget's own, or the upper end of the bracket.
  const auto above = std::lower_bound(points.begin(), points.end(), budget,
                                      [](const BudgetPoint& p, double b) { return p.budget < b; });
  out.hi = static_cast<std::size_t>(above - points.begin());
  if (above->budget == budget) {
    out.lo = out.hi;
    out.errorPct = above->errorPct;
    return true;
  }
  out.lo = out.hi - 1;
  const BudgetPoint& a = points[out.lo];
  const BudgetPoint& b = points[out.hi];
  // 0 < a.budget < budget < b.budget: the span is positive.
  const double span = std::log(b.budget) - std::log(a.budget);
  const double t = (std::log(budget) - std::log(a.budget)) / span;
  out.errorPct = a.errorPct + t * (b.errorPct - a.errorPct);
  return true;
}

std::string errorAtCell(const Family& f, double exactUs) {
  const std::vector<BudgetPoint> points = usable(f.points);
  Bracket at;
  if (bracketOf(points, exactUs, at)) {
    if (at.lo == at.hi) return format("%.2f", at.errorPct) + " (measured at that budget)";
    return format("%.2f", at.errorPct) + " (interpolated between " +
           format("%g", points[at.lo].budget) + " and " + format("%g", points[at.hi].budget) +
           " us)";
  }
  if (points.empty()) return "no positive time budget with an error rate measured";
  return "outside the measured budgets (" + format("%g", points.front().budget) + " to " +
         format("%g", points.back().budget) + " us)";
}

std::string exactTimeTable(const std::vector<Family>& families,
                           const std::vector<SummaryRow>& rows) {
  const auto exact = std::find_if(rows.begin(), rows.end(),
                                  [](const SummaryRow& r) { return r.method == "exact"; });
  const bool anyAdb = std::any_of(families.begin(), families.end(),
                                  [](const Family& f) { return f.kind == "adb"; });
  if (!anyAdb) return "";
  if (exact == rows.end() || !(exact->meanUs > 0.0)) {
    return "\nADB at exact mode's mean query time: exact mode did not run.\n";
  }
  std::string out = "\nADB's error at a time budget equal to exact mode's mean query time (" +
                    format("%.1f", exact->meanUs) +
                    " us), interpolated linearly in log(budget) between the two measured time "
                    "budgets around it (a budget of 0 has no logarithm and is left out):\n\n"
                    "| p_min | k_min | error % |\n|---:|---:|---|\n";
  for (const Family& f : families) {
    if (f.kind != "adb") continue;
    out += "| " + format("%g", f.params.pMin) + " | " + std::to_string(f.params.kMin) + " | " +
           errorAtCell(f, exact->meanUs) + " |\n";
  }
  return out;
}

std::string modelPart(const std::vector<SummaryRow>& rows) {
  if (rows.empty()) return "";
  std::string out = "\n### " + rows.front().model + " (" + std::to_string(rows.front().triangles) +
                    " triangles)\n\n";
  const std::vector<Family> families = familiesOf(rows);
  if (families.empty()) return out + "No budgeted method ran.\n";
  return out + thresholdTable(families) + exactTimeTable(families, rows);
}

}  // namespace

bool interpolateErrorPct(const std::vector<BudgetPoint>& points, double budget,
                         double& errorPct) {
  Bracket at;
  if (!bracketOf(usable(points), budget, at)) return false;
  errorPct = at.errorPct;
  return true;
}

std::string budgetsSection(const std::vector<std::vector<SummaryRow>>& perModel) {
  std::string out =
      "\n## Budgets\n\nPer budgeted method, the smallest budget whose error rate is at most " +
      format("%g", kLooseErrorPct) + " % and at most " + format("%g", kTightErrorPct) +
      " % (error and mean time at that budget), or \"not reached\" within the measured "
      "budgets.\n";
  for (const std::vector<SummaryRow>& rows : perModel) out += modelPart(rows);
  return out;
}

}  // namespace adb::tradeoff
