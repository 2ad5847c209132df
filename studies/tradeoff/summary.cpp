// Aggregating one model's query records into summary rows, and writing them.
#include "summary.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <optional>
#include <stdexcept>

#include "calibration.h"
#include "csv_format.h"
#include "judging.h"
#include "pooling.h"

namespace adb::tradeoff {

const char* const kSummaryCsvHeader =
    "model,triangles,method,p_min,k_min,budget_us,queries,overlapping,mean_us,p95_us,error_pct,"
    "ece,mean_confidence,mean_node_pairs,speedup_vs_exact,speedup_vs_gimpact,speedup_vs_fcl";

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

double meanUs(const MethodRecords& m) {
  double sum = 0.0;
  for (const QueryRecord& q : m.queries) sum += q.timeNs;
  return m.queries.empty() ? kNaN : sum / static_cast<double>(m.queries.size()) / 1000.0;
}

// Nearest-rank 95th percentile.
double p95Us(const MethodRecords& m) {
  if (m.queries.empty()) return kNaN;
  std::vector<double> t;
  t.reserve(m.queries.size());
  for (const QueryRecord& q : m.queries) t.push_back(q.timeNs);
  const auto rank = static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(t.size())));
  const std::size_t k = std::clamp<std::size_t>(rank, 1, t.size()) - 1;
  std::nth_element(t.begin(), t.begin() + static_cast<std::ptrdiff_t>(k), t.end());
  return t[k] / 1000.0;
}

// Percent of wrong answers among the judged ones; NaN without a reference or a query to
// count.
double errorPct(const std::vector<JudgedAnswer>* judged) {
  if (!judged || judged->empty()) return kNaN;
  const auto wrong = std::count_if(judged->begin(), judged->end(),
                                   [](const JudgedAnswer& a) { return !a.right; });
  return 100.0 * static_cast<double>(wrong) / static_cast<double>(judged->size());
}

// ECE of a method that estimates its confidence; NaN otherwise (and without a reference).
double ece(const MethodRecords& m, const std::vector<JudgedAnswer>* judged) {
  if (!m.params.estimates || !judged) return kNaN;
  return expectedCalibrationError(reliabilityBins(*judged));
}

double meanConfidence(const MethodRecords& m) {
  double sum = 0.0;
  for (const QueryRecord& q : m.queries) sum += q.confidence;
  return m.queries.empty() ? kNaN : sum / static_cast<double>(m.queries.size());
}

double meanNodePairs(const MethodRecords& m) {
  double sum = 0.0;
  for (const QueryRecord& q : m.queries) {
    if (q.nodePairs < 0) return kNaN;  // the method cannot tell
    sum += static_cast<double>(q.nodePairs);
  }
  return m.queries.empty() ? kNaN : sum / static_cast<double>(m.queries.size());
}

double speedup(const MethodRecords* peer, double ownMeanUs) {
  return peer && ownMeanUs > 0.0 ? meanUs(*peer) / ownMeanUs : kNaN;
}

std::string number(double v, const char* fmt) { return formatOrEmpty(fmt, v); }

std::string csvLine(const SummaryRow& r) {
  return csvField(r.model) + ',' + std::to_string(r.triangles) + ',' + r.method + ',' +
         methodParamFields(r.params) + ',' + std::to_string(r.queries) + ',' +
         std::to_string(r.overlapping) + ',' + number(r.meanUs, "%.6g") + ',' +
         number(r.p95Us, "%.6g") + ',' + number(r.errorPct, "%.6g") + ',' +
         number(r.ece, "%.6g") + ',' + number(r.meanConfidence, "%.6g") + ',' +
         number(r.meanNodePairs, "%.6g") + ',' +
         number(r.speedupVsExact, "%.6g") + ',' + number(r.speedupVsGimpact, "%.6g") + ',' +
         number(r.speedupVsFcl, "%.6g");
}

// The budget column: the time budget, "none" for ADB without one, empty otherwise (a work
// budget is in the method's name).
std::string budgetCell(const MethodParams& p) {
  if (std::isfinite(p.budgetUs)) return format("%g", p.budgetUs);
  return p.hasQuality && p.budgetPairs == 0 ? "none" : "";
}

std::string markdownLine(const SummaryRow& r) {
  const MethodParams& p = r.params;
  return "| " + r.model + " | " + std::to_string(r.triangles) + " | " + r.method + " | " +
         (p.hasQuality ? format("%g", p.pMin) : "") + " | " +
         (p.hasQuality ? std::to_string(p.kMin) : "") + " | " + budgetCell(p) + " | " +
         std::to_string(r.queries) + " | " + std::to_string(r.overlapping) + " | " +
         number(r.meanUs, "%.1f") + " | " + number(r.p95Us, "%.1f") + " | " +
         number(r.errorPct, "%.2f") + " | " + number(r.ece, "%.3f") + " | " +
         number(r.meanConfidence, "%.3f") + " | " + number(r.meanNodePairs, "%.0f") + " | " +
         number(r.speedupVsExact, "%.2f") + " | " + number(r.speedupVsGimpact, "%.2f") + " | " +
         number(r.speedupVsFcl, "%.2f") + " |";
}

std::ofstream openForWriting(const std::string& path) {
  std::ofstream out(path, std::ios::trunc);
  if (!out) throw std::runtime_error("cannot write " + path);
  return out;
}

void finish(std::ofstream& out, const std::string& path) {
  out.flush();
  if (!out) throw std::runtime_error("writing " + path + " failed");
}

}  // namespace

namespace {

// The row of `m`; `judged`: its answers judged against the run's reference (nullptr
// without one); `overlapping`: its queries whose root boxes overlap.
SummaryRow rowOf(const ModelResult& result, const MethodRecords& m,
                 const std::vector<JudgedAnswer>* judged, std::size_t overlapping) {
  SummaryRow row;
  row.model = result.label;
  row.triangles = result.triangles;
  row.method = m.name;
  row.params = m.params;
  row.queries = m.queries.size();
  row.overlapping = overlapping;
  row.meanUs = meanUs(m);
  row.p95Us = p95Us(m);
  row.errorPct = errorPct(judged);
  row.ece = ece(m, judged);
  row.meanConfidence = meanConfidence(m);
  row.meanNodePairs = meanNodePairs(m);
  row.speedupVsExact = speedup(findMethod(result, "exact"), row.meanUs);
  row.speedupVsGimpact = speedup(findMethod(result, "gimpact"), row.meanUs);
  row.speedupVsFcl = speedup(findMethod(result, "fcl"), row.meanUs);
  return row;
}

SummaryRow summarizeMethod(const ModelResult& result, const MethodRecords& m) {
  const MethodRecords* reference = referenceOf(result);
  std::vector<JudgedAnswer> judged;
  if (reference) judged = judgeAnswers(result, m, *reference);
  const auto overlapping = static_cast<std::size_t>(
      std::count(result.rootsOverlap.begin(), result.rootsOverlap.end(), true));
  return rowOf(result, m, reference ? &judged : nullptr, overlapping);
}

}  // namespace

std::vector<SummaryRow> summarize(const ModelResult& result) {
  std::vector<SummaryRow> rows;
  for (const MethodRecords& m : result.methods) rows.push_back(summarizeMethod(result, m));
  // Speedups compare mean times, so the peers' own records serve the pool as they are.
  if (const std::optional<PooledAdb> pool = pooledAdb(result)) {
    rows.push_back(rowOf(result, pool->records, pool->hasReference ? &pool->judged : nullptr,
                         pool->overlapping));
  }
  return rows;
}

void writeSummaryCsv(const std::string& path, const std::vector<SummaryRow>& rows) {
  std::ofstream out = openForWriting(path);
  out << kSummaryCsvHeader << '\n';
  for (const SummaryRow& r : rows) out << csvLine(r) << '\n';
  finish(out, path);
}

void writeSummaryMarkdown(const std::string& path, const std::vector<SummaryRow>& rows,
                          const RunNotes& notes, const std::string& sections) {
  std::ofstream out = openForWriting(path);
  out << "# adb-tradeoff summary\n\n";
  for (const std::string& line : notes.lines) out << line << '\n';
  out << "\n| model | triangles | method | p_min | k_min | budget us | queries | overlapping | "
         "mean us | p95 us | error % | ece | mean confidence | mean node pairs | vs exact | "
         "vs gimpact | vs fcl |\n";
  out << "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const SummaryRow& r : rows) out << markdownLine(r) << '\n';
  out << "\n`error %`: wrong yes/no answers against the exact mode (FCL when exact did not run) "
         "among the queries whose root boxes overlap. `ece`: expected calibration error of the "
         "row's confidence over the same queries (reliability.csv; methods that estimate their "
         "confidence only). `adb-pooled`: every adb and adb-work setting of the model pooled "
         "(its queries and overlapping count pooled queries). `vs X`: X's mean time / this "
         "row's mean time on the same poses (above 1: this row is faster).\n";
  out << sections;
  finish(out, path);
}

}  // namespace adb::tradeoff
