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
    "error_pct,mean_confidence,reference";

namespace {

// Sums over the queries at one distance.
struct AtDistance {
  std::size_t queries = 0, overlapping = 0, wrong = 0;
  double timeNs = 0.0, confidence = 0.0;
};

// `sum` over the judged queries, NaN (an empty field) when none was judged.
double meanOver(double sum, std::size_t judged) {
  return judged > 0 ? sum / static_cast<double>(judged) : std::nan("");
}

void writeMethod(std::ofstream& out, const ModelResult& result, const MethodRecords& m,
                 const MethodRecords* reference) {
  std::map<double, AtDistance> byDistance;  // ordered: rows by increasing distance
  const std::size_t n = std::min(m.queries.size(), result.distance.size());
  for (std::size_t i = 0; i < n; ++i) {
    AtDistance& d = byDistance[result.distance[i]];
    ++d.queries;
    d.timeNs += m.queries[i].timeNs;
  }
  if (reference) {
    forEachJudged(result, m, *reference, [&](std::size_t pose, const JudgedAnswer& answer) {
      if (pose >= n) return;
      AtDistance& d = byDistance[result.distance[pose]];
      ++d.overlapping;
      d.confidence += answer.confidence;
      d.wrong += answer.right ? 0 : 1;
    });
  }
  const std::string head = csvField(result.label) + ',' + std::to_string(result.triangles) + ',' +
                           m.name + ',' + methodParamFields(m.params) + ',';
  const std::string referenceName = reference ? reference->name : "";
  for (const auto& [distance, d] : byDistance) {
    out << head << format("%.9g", distance) << ',' << d.queries << ','
        << format("%.6g", d.timeNs / 1000.0 / static_cast<double>(d.queries)) << ','
        << d.overlapping << ','
        << formatOrEmpty("%.6g", meanOver(100.0 * static_cast<double>(d.wrong), d.overlapping))
        << ',' << formatOrEmpty("%.6g", meanOver(d.confidence, d.overlapping)) << ','
        << referenceName << '\n';
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
