// Calibration arithmetic: does a method's confidence mean what it says? Answers are put in
// 10 equal-width confidence bins, [0, 0.1), [0.1, 0.2), ..., [0.9, 1.0] (1.0 goes in the
// last bin); per bin the mean confidence and the fraction of right answers (a reliability
// diagram), and the expected calibration error
//   ECE = sum over bins of (count_b / N) * |fraction_right_b - mean_confidence_b|.
// A perfectly calibrated method has ECE 0; one that says 0.99 and is right half the time,
// 0.49.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

namespace adb::tradeoff {

/// One answer, judged against the reference.
struct JudgedAnswer {
  double confidence = 0.0;  ///< the method's estimate that its answer is right, [0, 1]
  bool right = false;       ///< the answer equals the reference's
};

inline constexpr int kCalibrationBins = 10;

struct CalibrationBin {
  double lo = 0.0, hi = 0.0;  ///< [lo, hi); the last bin includes hi = 1
  std::size_t count = 0;
  double meanConfidence = 0.0;  ///< NaN when the bin is empty
  double fractionRight = 0.0;   ///< NaN when the bin is empty
};

using ReliabilityBins = std::array<CalibrationBin, kCalibrationBins>;

/// The bin of a confidence: confidences below 0 go in the first bin, above 1 in the last,
/// NaN in the first (a method should never report one; it must not crash the report).
int calibrationBin(double confidence);

/// The reliability diagram of `answers`.
ReliabilityBins reliabilityBins(const std::vector<JudgedAnswer>& answers);

/// ECE of the binned answers; NaN when there are none.
double expectedCalibrationError(const ReliabilityBins& bins);

}  // namespace adb::tradeoff
