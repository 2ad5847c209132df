// The calibration arithmetic (calibration.h): confidence bins with their edges, per-bin mean
// confidence and fraction right, and the expected calibration error of a hand-made set of
// answers whose ECE is worked out below.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "calibration.h"

namespace adb::tradeoff {
namespace {

std::vector<JudgedAnswer> repeated(double confidence, int right, int wrong) {
  std::vector<JudgedAnswer> out;
  for (int i = 0; i < right; ++i) out.push_back({confidence, true});
  for (int i = 0; i < wrong; ++i) out.push_back({confidence, false});
  return out;
}

void append(std::vector<JudgedAnswer>& to, const std::vector<JudgedAnswer>& more) {
  to.insert(to.end(), more.begin(), more.end());
}

TEST(Reliability, BinEdgesAreClosedBelowAndOneGoesInTheLastBin) {
  for (int k = 0; k < kCalibrationBins; ++k) {
    EXPECT_EQ(calibrationBin(k / 10.0), k) << k / 10.0;       // an edge opens its bin
    EXPECT_EQ(calibrationBin(k / 10.0 + 0.05), k) << k / 10.0 + 0.05;
    if (k > 0) {
      EXPECT_EQ(calibrationBin(std::nextafter(k / 10.0, 0.0)), k - 1) << k / 10.0;
    }
  }
  EXPECT_EQ(calibrationBin(1.0), 9);
  EXPECT_EQ(calibrationBin(0.0), 0);
  EXPECT_EQ(calibrationBin(-0.2), 0);  // out of range: clamped, never out of bounds
  EXPECT_EQ(calibrationBin(1.5), 9);
  EXPECT_EQ(calibrationBin(std::nan("")), 0);
}

TEST(Reliability, HandMadeAnswersHaveTheKnownBinsAndEce) {
  // 4 answers at 0.95 (3 right), 2 at 0.55 (both right), 4 at 0.05 (none right): N = 10,
  // ECE = 0.4 * |0.75 - 0.95| + 0.2 * |1 - 0.55| + 0.4 * |0 - 0.05| = 0.08 + 0.09 + 0.02.
  std::vector<JudgedAnswer> answers = repeated(0.95, 3, 1);
  append(answers, repeated(0.55, 2, 0));
  append(answers, repeated(0.05, 0, 4));
  const ReliabilityBins bins = reliabilityBins(answers);
  EXPECT_EQ(bins[9].count, 4u);
  EXPECT_NEAR(bins[9].meanConfidence, 0.95, 1e-12);
  EXPECT_NEAR(bins[9].fractionRight, 0.75, 1e-12);
  EXPECT_EQ(bins[5].count, 2u);
  EXPECT_NEAR(bins[5].fractionRight, 1.0, 1e-12);
  EXPECT_EQ(bins[0].count, 4u);
  EXPECT_NEAR(bins[0].fractionRight, 0.0, 1e-12);
  for (int b : {1, 2, 3, 4, 6, 7, 8}) {
    EXPECT_EQ(bins[static_cast<std::size_t>(b)].count, 0u) << b;
    EXPECT_TRUE(std::isnan(bins[static_cast<std::size_t>(b)].meanConfidence)) << b;
    EXPECT_TRUE(std::isnan(bins[static_cast<std::size_t>(b)].fractionRight)) << b;
  }
  for (int b = 0; b < kCalibrationBins; ++b) {
    EXPECT_NEAR(bins[static_cast<std::size_t>(b)].lo, b * 0.1, 1e-12);
    EXPECT_NEAR(bins[static_cast<std::size_t>(b)].hi, (b + 1) * 0.1, 1e-12);
  }
  EXPECT_NEAR(expectedCalibrationError(bins), 0.19, 1e-12);
}

TEST(Reliability, MixedConfidencesInOneBinAreAveraged) {
  // 0.62 (right) and 0.68 (wrong) share bin 6: mean 0.65, fraction right 0.5, ECE 0.15.
  const std::vector<JudgedAnswer> answers{{0.62, true}, {0.68, false}};
  const ReliabilityBins bins = reliabilityBins(answers);
  EXPECT_EQ(bins[6].count, 2u);
  EXPECT_NEAR(bins[6].meanConfidence, 0.65, 1e-12);
  EXPECT_NEAR(bins[6].fractionRight, 0.5, 1e-12);
  EXPECT_NEAR(expectedCalibrationError(bins), 0.15, 1e-12);
}

TEST(Reliability, CalibratedAnswersHaveZeroEce) {
  std::vector<JudgedAnswer> answers = repeated(0.8, 8, 2);  // says 0.8, right 80 %
  append(answers, repeated(1.0, 5, 0));
  EXPECT_NEAR(expectedCalibrationError(reliabilityBins(answers)), 0.0, 1e-12);
}

TEST(Reliability, NoAnswersGiveNoEce) {
  const ReliabilityBins bins = reliabilityBins({});
  for (const CalibrationBin& bin : bins) EXPECT_EQ(bin.count, 0u);
  EXPECT_TRUE(std::isnan(expectedCalibrationError(bins)));
}

}  // namespace
}  // namespace adb::tradeoff
