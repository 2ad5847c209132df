// Writing reliability.csv.
#include "reliability.h"

#include <cmath>
#include <fstream>
#include <optional>
#include <stdexcept>

#include "calibration.h"
#include "csv_format.h"
#include "judging.h"
#include "pooling.h"

namespace adb::tradeoff {

const char* const kReliabilityCsvHeader =
    "model,triangles,method,p_min,k_min,budget_us,bin,bin_lo,bin_hi,count,mean_confidence,"
    "fraction_right";

namespace {

std::string number(double v) { return formatOrEmpty("%.6g", v); }

void writeGroup(std::ostream& out, const ModelResult& result, const MethodRecords& method,
                const std::vector<JudgedAnswer>& judged) {
  const ReliabilityBins bins = reliabilityBins(judged);
  const std::string prefix = csvField(result.label) + ',' + std::to_string(result.triangles) +
                             ',' + method.name + ',' + methodParamFields(method.params) + ',';
  for (std::size_t b = 0; b < bins.size(); ++b) {
    const CalibrationBin& bin = bins[b];
    out << prefix << b << ',' << format("%g", bin.lo) << ',' << format("%g", bin.hi) << ','
        << bin.count << ',' << number(bin.meanConfidence) << ',' << number(bin.fractionRight)
        << '\n';
  }
}

}  // namespace

void writeReliabilityRows(std::ostream& out, const ModelResult& result) {
  const MethodRecords* reference = referenceOf(result);
  if (!reference) return;
  for (const MethodRecords& m : result.methods) {
    if (m.params.estimates) writeGroup(out, result, m, judgeAnswers(result, m, *reference));
  }
  // The pool is judged against the same reference: it holds answers here.
  if (const std::optional<PooledAdb> pool = pooledAdb(result)) {
    writeGroup(out, result, pool->records, pool->judged);
  }
}

void writeReliabilityCsv(const std::string& path, const std::vector<ModelResult>& done) {
  std::ofstream out(path, std::ios::trunc);
  if (!out) throw std::runtime_error("cannot write " + path);
  out << kReliabilityCsvHeader << '\n';
  for (const ModelResult& r : done) writeReliabilityRows(out, r);
  out.flush();
  if (!out) throw std::runtime_error("writing " + path + " failed");
}

}  // namespace adb::tradeoff
