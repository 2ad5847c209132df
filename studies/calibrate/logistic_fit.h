// The fit behind the collision estimate (adb/core/collision_estimate.h): a logistic
// regression over the estimate's features whose weights on evidence are held >= 0, and a
// monotone recalibration of its output, each weighting every case (a model, or a pair of
// models) equally however many samples it gave.
#pragma once

#include <string>
#include <vector>


namespace adb::calibrate {

using Weights = std::vector<double>;

/// One labelled sample: a traversal's state, or one open pair of it.
struct Sample {
  std::vector<double> f;
  bool truth = false;
  int checkpoint = 0;  ///< budget stops: the work budget was 2^checkpoint node pairs
};

/// The samples of one case.
struct CaseSamples {
  std::string name;
  std::vector<Sample> samples;
};

/// sigmoid(w . f), in [0, 1]; 0.5 for a NaN sum.
double sigmoidDot(const std::vector<double>& f, const Weights& w);

/// Newton's method on the weighted log-loss with an active set that keeps weight i >= 0 where
/// nonNegative[i] (evidence: more of it never lowers the estimate); as many weights as flags.
Weights fitLogistic(const std::vector<CaseSamples>& cases, const std::vector<bool>& nonNegative);

/// Pool-adjacent-violators on (logistic estimate, label) pairs of every case, each case
/// weighing 1: a non-decreasing map from the estimate to the observed frequency, as
/// knots at the pooled blocks' mean estimates. Where the logistic model is over- or
/// under-confident in a way its features cannot express, the map pulls its output to what
/// the fit set observed.
struct MonotoneMap {
  std::vector<double> x, y;  ///< knots, x increasing, y non-decreasing
};
MonotoneMap fitMonotone(const std::vector<CaseSamples>& cases, const Weights& w, int knots);

}  // namespace adb::calibrate
