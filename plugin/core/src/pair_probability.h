// Internal: the probability of one node pair of two posed trees (paper §3.5-3.6), from the
// cell counts s, s_A, s_B the pair kernel measures (the [open] choices are documented in
// pair_probability.cpp and in docs/probability-model.md).
#pragma once

#include "adb/core/probability.h"
#include "adb/core/tree.h"
#include "pair_kernel.h"
#include "relative_frame.h"

namespace adb::detail {

/// Per-tree constants the estimate reads.
struct TreeConstants {
  const AdbTree* tree;
  int maxDepth;
};

struct PairEstimate {
  bool overlap = false;
  double lower = 0.0;  // Eq. 3: the priority and the acceptance test
  double upper = 0.0;  // Pr[X >= 1]
  double expected = 0.0;  // E[X] before rounding, uncapped (min(1, E[X]) bounds Pr[X >= 1])
  int s = 0, sA = 0, sB = 0;
};

/// The probability of an overlapping pair from its cell counts (PairKernel::cellCounts) at
/// the given depths (overlap is set).
PairEstimate estimateOverlapping(const CellCounts& counts, int depthA, int depthB, int maxDepthA,
                                 int maxDepthB);

/// Overlap test plus, when they overlap, the probability of one pair given by index.
PairEstimate estimatePair(const TreeConstants& ta, std::uint32_t a, int depthA,
                          const TreeConstants& tb, std::uint32_t b, int depthB,
                          const RelativeFrame& frame);
bool nodesOverlap(const TreeConstants& ta, std::uint32_t a, const TreeConstants& tb,
                  std::uint32_t b, const RelativeFrame& frame);
/// PairKernel::occupiedFill of one pair; 0 when the pair is proven apart.
double pairFill(const TreeConstants& ta, std::uint32_t a, const TreeConstants& tb,
                std::uint32_t b, const RelativeFrame& frame);

}  // namespace adb::detail
