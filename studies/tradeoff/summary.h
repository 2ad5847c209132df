// The per-model summary of a run: one row per model, method and parameter combination (mean
// and p95 time, error rate against the exact answer among queries whose root boxes overlap,
// the expected calibration error of methods that estimate their confidence, mean confidence
// and node pairs, speedups against each peer run on the same poses), plus one "adb-pooled"
// row over all ADB settings, written as summary.csv (fixed columns, read by
// plot_tradeoff.py) and summary.md.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "method.h"
#include "results.h"

namespace adb::tradeoff {

/// The header line of summary.csv, exactly.
extern const char* const kSummaryCsvHeader;

/// Values that a row cannot have (no reference method, no node counts, peer not run) are
/// NaN and written as empty fields.
struct SummaryRow {
  std::string model;
  std::size_t triangles = 0;
  std::string method;
  MethodParams params;
  std::size_t queries = 0;
  std::size_t overlapping = 0;
  double meanUs = 0.0;
  double p95Us = 0.0;
  double errorPct = 0.0;
  double ece = 0.0;  ///< NaN for methods without an estimate (calibration.h)
  double meanConfidence = 0.0;
  double meanNodePairs = 0.0;
  double speedupVsExact = 0.0;
  double speedupVsGimpact = 0.0;
  double speedupVsFcl = 0.0;
};

/// The rows of one model, in method order, then "adb-pooled" when an ADB setting ran (its
/// queries and overlapping count the pooled queries). The error reference is "exact" if it
/// ran, else "fcl", else none.
std::vector<SummaryRow> summarize(const ModelResult& result);

/// Free-form lines printed above the Markdown table (command line, machine, policy).
struct RunNotes {
  std::vector<std::string> lines;
};

/// Writes (truncates) the files; throws std::runtime_error when writing fails.
void writeSummaryCsv(const std::string& path, const std::vector<SummaryRow>& rows);
/// `sections`: Markdown appended after the table (the budgets section).
void writeSummaryMarkdown(const std::string& path, const std::vector<SummaryRow>& rows,
                          const RunNotes& notes, const std::string& sections);

}  // namespace adb::tradeoff
