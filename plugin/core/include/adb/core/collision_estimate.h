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
  /// The query ended on its own (k_min reached, or its queue emptied by pruning) rather than
  /// on a budget. Such states are fitted apart: there the estimate is the probability that
  /// the paper's answer ("collision" at k_min, "no" after pruning) is right.
  bool quality = false;
  bool reachedKMin = false;  ///< with quality: it ended at k_min (else its queue emptied)
};

inline constexpr int kEstimateFeatures = 8;
using EstimateWeights = std::array<double, kEstimateFeatures>;

/// The model's features: 1, frontierUnion, log(frontierDoubt + prunedDoubt + 1e-3),
/// log(1 + collisionPairs), log(1 + openPairs), bestOpen, log(expectedCells + 1e-3),
/// [a quality stop on an emptied queue]; each clamped so that every evidence, however
/// extreme, gives finite features.
std::array<double, kEstimateFeatures> estimateFeatures(const Evidence& e);

/// Which features count as evidence for a collision: their weights are kept >= 0.
inline constexpr std::array<bool, kEstimateFeatures> kEvidenceFeature{
    false, true, true, true, false, true, true, false};

/// sigmoid(w . features), in [0, 1]; 0.5 where the sum is NaN (only NaN weights make one).
/// With the budget weights this is P(collision); with the quality weights, P(the paper's
/// answer is right).
double logisticEstimate(const std::array<double, kEstimateFeatures>& features,
                        const EstimateWeights& w);

/// logisticEstimate(estimateFeatures(e), w).
double collisionProbability(const Evidence& e, const EstimateWeights& w);

/// P(collision) with the weights fitted for this library: for a budget stop the budget model;
/// for a quality stop the probability that the paper's answer is right, turned into
/// P(collision) by that answer (see the .cpp for the fit's command).
double collisionProbability(const Evidence& e);

}  // namespace adb
