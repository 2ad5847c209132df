// The probability that two posed meshes collide, from what a traversal has seen when a budget
// stops it without a certain answer.
//
// [open] The paper answers "no collision" whenever it is cut and gives no probability for its
// answer. Ours: the frontier (the node pairs still open) is a partition of everything left
// unresolved, so no open pair is nested in another; its Eq. 3 bounds and its Pr[X >= 1]
// summarise the model's belief about that remainder. Pairs near each other are not
// independent, and Eq. 3 is a bound, not a probability, so the summary goes through a
// logistic model fitted on generated meshes (studies/calibrate, docs/probability-model.md):
// P(collision) = sigmoid(w . features). Its weights on the evidence are non-negative, so more
// evidence for a collision never lowers P.
#pragma once

#include <array>
#include <cstdint>

namespace adb {

/// What a traversal has seen when it stops undecided.
struct Evidence {
  double frontierUnion = 0.0;  ///< 1 - prod(1 - p) over the open pairs' Eq. 3 bounds p
  double frontierDoubt = 0.0;  ///< sum of Pr[X >= 1] over the open pairs (min(1, E[X]) where
                               ///< rounding left one side no cell)
  double prunedDoubt = 0.0;    ///< sum of min(1, E[X]) over the pairs pruned for p = 0
  double bestOpen = 0.0;       ///< the largest Eq. 3 bound among the open pairs
  std::uint32_t openPairs = 0;
  std::uint32_t collisionPairs = 0;  ///< pairs accepted with p > p_min (the paper's k)
  double expectedCells = 0.0;  ///< sum of E[X] (collision cells) over open and pruned pairs
  /// What the cell model cannot speak for (issue 43). A pair of nodes of a few large
  /// triangles or of slivers (the pairs QuerySettings::minTrianglesToAccept keeps from being
  /// accepted, and every pair of leaves) has E[X] near 0 whether its triangles touch or not:
  /// read as the model reads it, an open frontier of such pairs says "no". Their evidence is
  /// how full of triangles both nodes are where their boxes meet (the occupied cells) instead.
  double blindUnion = 0.0;     ///< 1 - prod(1 - k) over the open blind pairs' priority keys k
  std::uint32_t blindPairs = 0;  ///< open pairs the model is blind to
  /// How full both roots are where their boxes meet (PairKernel::occupiedFill): the base rate
  /// of the pose, which speaks when nothing below the roots has been seen.
  double rootFill = 0.0;
  std::uint64_t nodePairs = 0;  ///< node pairs evaluated so far: how far the query got
  /// The fills of the open pairs first in the queue (at most kFilledOpenPairs of them): what the
  /// overlap of the open boxes and their occupied cells says where the cell model says little
  /// (large flat triangles cross cells without covering enough of them to count).
  double openFillUnion = 0.0;  ///< 1 - prod(1 - fill)
  double openFillMax = 0.0;
  /// The query ended on its own (k_min reached, or its queue emptied by pruning) rather than
  /// on a budget. Such states are fitted apart: there the estimate is the probability that
  /// the paper's answer ("collision" at k_min, "no" after pruning) is right.
  bool quality = false;
  bool reachedKMin = false;  ///< with quality: it ended at k_min (else its queue emptied)
};

/// How many open pairs a stop works out the fill of (a posed pair of boxes and two counts of
/// cells each, about 0.1 us): the first in the queue's order, the likeliest.
inline constexpr int kFilledOpenPairs = 8;

inline constexpr int kEstimateFeatures = 14;
using EstimateWeights = std::array<double, kEstimateFeatures>;

/// The model's features: 1, frontierUnion, log(frontierDoubt + prunedDoubt + 1e-3),
/// log(1 + collisionPairs), log(1 + openPairs), bestOpen, log(expectedCells + 1e-3),
/// [a quality stop on an emptied queue], blindUnion, log(1 + blindPairs), rootFill,
/// log(1 + nodePairs), openFillUnion, openFillMax; each clamped so that every evidence, however extreme, gives finite
/// features.
std::array<double, kEstimateFeatures> estimateFeatures(const Evidence& e);

/// Which features count as evidence for a collision: their weights are kept >= 0.
inline constexpr std::array<bool, kEstimateFeatures> kEvidenceFeature{
    false, true, true, true, false, true, true, false, true, false, true, false, true, true};

/// sigmoid(w . features), in [0, 1]; 0.5 where the sum is NaN (only NaN weights make one).
/// With the budget weights this is P(collision); with the quality weights, P(the paper's
/// answer is right).
double logisticEstimate(const std::array<double, kEstimateFeatures>& features,
                        const EstimateWeights& w);

/// The monotone recalibration a budget stop's logistic estimate goes through: the
/// piecewise-linear map through knots (x[i], y[i]), x increasing and y non-decreasing, held
/// at y[0] below x[0] and at y[n-1] above x[n-1]; p itself for n = 0. Non-decreasing, so more
/// evidence still never lowers the estimate.
double monotoneMap(double p, const double* x, const double* y, int n);

/// logisticEstimate(estimateFeatures(e), w).
double collisionProbability(const Evidence& e, const EstimateWeights& w);

/// P(collision) with the weights fitted for this library: for a budget stop the budget model;
/// for a quality stop the probability that the paper's answer is right, turned into
/// P(collision) by that answer (see the .cpp for the fit's command).
double collisionProbability(const Evidence& e);

}  // namespace adb
