// Binning answers by confidence, and the expected calibration error.
#include "calibration.h"

#include <cmath>
#include <limits>

namespace adb::tradeoff {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Bin b's lower edge, computed the same way wherever it is needed (binning and the file),
// so that a confidence printed as 0.3 and the edge printed as 0.3 fall on the same side.
double lowerEdge(int b) { return static_cast<double>(b) / kCalibrationBins; }

}  // namespace

int calibrationBin(double confidence) {
  if (!(confidence > 0.0)) return 0;  // also NaN
  if (confidence >= 1.0) return kCalibrationBins - 1;
  int b = static_cast<int>(std::floor(confidence * kCalibrationBins));
  // The product may round across an edge: settle against the edges themselves.
  if (b >= kCalibrationBins) b = kCalibrationBins - 1;
  if (b > 0 && confidence < lowerEdge(b)) --b;
  if (b + 1 < kCalibrationBins && confidence >= lowerEdge(b + 1)) ++b;
  return b;
}

ReliabilityBins reliabilityBins(const std::vector<JudgedAnswer>& answers) {
  ReliabilityBins bins{};
  std::array<double, kCalibrationBins> confidenceSum{}, rightCount{};
  for (const JudgedAnswer& a : answers) {
    const int b = calibrationBin(a.confidence);
    ++bins[static_cast<std::size_t>(b)].count;
    confidenceSum[static_cast<std::size_t>(b)] += std::isnan(a.confidence) ? 0.0 : a.confidence;
    rightCount[static_cast<std::size_t>(b)] += a.right ? 1.0 : 0.0;
  }
  for (int b = 0; b < kCalibrationBins; ++b) {
    CalibrationBin& bin = bins[static_cast<std::size_t>(b)];
    bin.lo = lowerEdge(b);
    bin.hi = lowerEdge(b + 1);
    const double n = static_cast<double>(bin.count);
    bin.meanConfidence = bin.count == 0 ? kNaN : confidenceSum[static_cast<std::size_t>(b)] / n;
    bin.fractionRight = bin.count == 0 ? kNaN : rightCount[static_cast<std::size_t>(b)] / n;
  }
  return bins;
}

double expectedCalibrationError(const ReliabilityBins& bins) {
  std::size_t total = 0;
  for (const CalibrationBin& bin : bins) total += bin.count;
  if (total == 0) return kNaN;
  double ece = 0.0;
  for (const CalibrationBin& bin : bins) {
    if (bin.count == 0) continue;  // empty bins weigh nothing (and hold NaN)
    ece += static_cast<double>(bin.count) / static_cast<double>(total) *
           std::abs(bin.fractionRight - bin.meanConfidence);
  }
  return ece;
}

}  // namespace adb::tradeoff
