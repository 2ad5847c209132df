// Aggregating one model's query records into summary rows, and writing them.
#include "summary.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <stdexcept>

#include "csv_format.h"

namespace adb::tradeoff {

const char* const kSummaryCsvHeader =
    "model,triangles,method,p_min,k_min,budget_us,queries,overlapping,mean_us,p95_us,error_pct,"
    "mean_confidence,mean_node_pairs,speedup_vs_exact,speedup_vs_gimpact,speedup_vs_fcl";

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

const MethodRecords* findMethod(const ModelResult& r, const std::string& name) {
  for (const MethodRecords& m : r.methods) {
    if (m.name == name) return &m;
  }
  return nullptr;
}

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

double errorPct(const ModelResult& r, const MethodRecords& m, const MethodRecords* reference) {
  if (!reference) return kNaN;
  std::size_t counted = 0, wrong = 0;
  for (std::size_t i = 0; i < m.queries.size(); ++i) {
    if (!r.rootsOverlap[i]) continue;
    ++counted;
    wrong += m.queries[i].collides != reference->queries[i].collides ? 1 : 0;
  }
  return counted == 0 ? kNaN : 100.0 * static_cast<double>(wrong) / static_cast<double>(counted);
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

std::string number(double v, const char* fmt) { return std::isnan(v) ? "" : format(fmt, v); }

std::string paramFields(const MethodParams& p) {
  if (!p.isAdb) return ",,";
  return format("%.15g", p.pMin) + ',' + std::to_string(p.kMin) + ',' +
         (std::isfinite(p.budgetUs) ? format("%.15g", p.budgetUs) : "");
}

std::string csvLine(const SummaryRow& r) {
  return csvField(r.model) + ',' + std::to_string(r.triangles) + ',' + r.method + ',' +
         paramFields(r.params) + ',' + std::to_string(r.queries) + ',' +
         std::to_string(r.overlapping) + ',' + number(r.meanUs, "%.6g") + ',' +
         number(r.p95Us, "%.6g") + ',' + number(r.errorPct, "%.6g") + ',' +
         number(r.meanConfidence, "%.6g") + ',' + number(r.meanNodePairs, "%.6g") + ',' +
         number(r.speedupVsExact, "%.6g") + ',' + number(r.speedupVsGimpact, "%.6g") + ',' +
         number(r.speedupVsFcl, "%.6g");
}

std::string markdownLine(const SummaryRow& r) {
  const MethodParams& p = r.params;
  const std::string budget = !p.isAdb ? "" : std::isfinite(p.budgetUs) ? format("%g", p.budgetUs) : "none";
  return "| " + r.model + " | " + std::to_string(r.triangles) + " | " + r.method + " | " +
         (p.isAdb ? format("%g", p.pMin) : "") + " | " + (p.isAdb ? std::to_string(p.kMin) : "") +
         " | " + budget + " | " + std::to_string(r.queries) + " | " +
         std::to_string(r.overlapping) + " | " + number(r.meanUs, "%.1f") + " | " +
         number(r.p95Us, "%.1f") + " | " + number(r.errorPct, "%.2f") + " | " +
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

std::vector<SummaryRow> summarize(const ModelResult& result) {
  const MethodRecords* exact = findMethod(result, "exact");
  const MethodRecords* gimpact = findMethod(result, "gimpact");
  const MethodRecords* fcl = findMethod(result, "fcl");
  const MethodRecords* reference = exact ? exact : fcl;
  const auto overlapping = static_cast<std::size_t>(
      std::count(result.rootsOverlap.begin(), result.rootsOverlap.end(), true));
  std::vector<SummaryRow> rows;
  for (const MethodRecords& m : result.methods) {
    SummaryRow row;
    row.model = result.label;
    row.triangles = result.triangles;
    row.method = m.name;
    row.params = m.params;
    row.queries = m.queries.size();
    row.overlapping = overlapping;
    row.meanUs = meanUs(m);
    row.p95Us = p95Us(m);
    row.errorPct = errorPct(result, m, reference);
    row.meanConfidence = meanConfidence(m);
    row.meanNodePairs = meanNodePairs(m);
    row.speedupVsExact = speedup(exact, row.meanUs);
    row.speedupVsGimpact = speedup(gimpact, row.meanUs);
    row.speedupVsFcl = speedup(fcl, row.meanUs);
    rows.push_back(row);
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
                          const RunNotes& notes) {
  std::ofstream out = openForWriting(path);
  out << "# adb-tradeoff summary\n\n";
  for (const std::string& line : notes.lines) out << line << '\n';
  out << "\n| model | triangles | method | p_min | k_min | budget us | queries | overlapping | "
         "mean us | p95 us | error % | mean confidence | mean node pairs | vs exact | "
         "vs gimpact | vs fcl |\n";
  out << "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const SummaryRow& r : rows) out << markdownLine(r) << '\n';
  out << "\n`error %`: wrong yes/no answers against the exact mode (FCL when exact did not run) "
         "among the queries whose root boxes overlap. `vs X`: X's mean time / this row's mean "
         "time on the same poses (above 1: this row is faster).\n";
  finish(out, path);
}

}  // namespace adb::tradeoff
