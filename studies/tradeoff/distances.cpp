// Per-distance figures of every method, judged as the summary judges.
#include "distances.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <stdexcept>

#include "csv_format.h"
#include "judging.h"

namespace adb::tradeoff {

const char* const kDistancesCsvHeader =
    "model,triangles,method,p_min,k_min,budget_us,distance,queries,mean_us,overlapping,"
    "error_pct,mean_confidence";

namespace {

// Sums over the queries at one distance.
struct AtDistance {
  std::size_t queries = 0, overlapping = 0, wrong = 0;
  double timeNs = 0.0, confidence = 0.0;
};

std::string optional(double value, std::size_t count) {
  return count > 0 ? format("%.6g", value) : "";
}

void writeMethod(std::ofstream& out, const ModelResult& result, const MethodRecords& m,
                 const MethodRecords* reference) {
  std::map<double, AtDistance> byDistance;  // ordered: rows by increasing distance
  const std::size_t n = std::min(m.queries.size(), result.distance.size());
  for (std::size_t i = 0; i < n; ++i) {
    AtDistance& d = byDistance[result.distance[i]];
    const QueryRecord& q = m.queries[i];
    ++d.queries;
    d.timeNs += q.timeNs;
    const bool judged = reference && i < reference->queries.size() &&
                        i < result.rootsOverlap.size() && result.rootsOverlap[i];
    if (!judged) continue;
    ++d.overlapping;
    d.confidence += q.confidence;
    d.wrong += q.collides != reference->queries[i].collides ? 1 : 0;
  }
  const std::string head = csvField(result.label) + ',' + std::to_string(result.triangles) + ',' +
                           m.name + ',' + methodParamFields(m.params) + ',';
  for (const auto& [distance, d] : byDistance) {
    const double share = d.overlapping > 0 ? 1.0 / static_cast<double>(d.overlapping) : 0.0;
    out << head << format("%.9g", distance) << ',' << d.queries << ','
        << format("%.6g", d.timeNs / 1000.0 / static_cast<double>(d.queries)) << ','
        << d.overlapping << ',' << optional(100.0 * static_cast<double>(d.wrong) * share, d.overlapping)
        << ',' << optional(d.confidence * share, d.overlapping) << '\n';
  }
}

}  // namespace

void writeDistancesCsv(const std::string& path, const std::vector<ModelResult>& done) {
  std::ofstream out(path, std::ios::trunc);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << kDistancesCsvHeader << '\n';
  for (const ModelResult& result : done) {
    const MethodRecords* reference = referenceOf(result);
    for (const MethodRecords& m : result.methods) writeMethod(out, result, m, reference);
  }
  out.flush();
  if (!out) throw std::runtime_error("writing " + path + " failed");
}

}  // namespace adb::tradeoff
