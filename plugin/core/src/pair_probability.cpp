// The node-pair probability of the ADB traversal (paper §3.5-3.6, Fig. 6 computeProb).
//
// [open] How s, s_A, s_B are computed (the paper defers to its companion paper). Our model,
// consistent with the average-case assumption (possible collision cells spread uniformly over
// a node's cells), with each node's near-cubic grid of side h (node_geometry.h):
//   1. The common cell is the coarser node's cell, side h_C = max(h_A, h_B).
//   2. s = the number of common cells the intersection of the two boxes touches: the
//      intersection box is computed in A's frame (A's box against the AABB of B's box) and
//      in B's frame, and per axis at least one cell counts (a thin overlap still meets a layer
//      of cells); the smaller of the two counts is kept, as both over-estimate.
//   3. A node's density rho = pc / cells is re-expressed at the common cell size: a surface
//      crossing n cells of side h crosses about n (h / h_C)^2 cells of side h_C, and there are
//      (h / h_C)^3 as many of those, so rho_C = min(1, rho * h_C / h).
//   4. s_X = round(rho_C(X) * s), clamped to 0..s.
// Then Eq. 3 with LB = (dA + dB) / (dmaxA + dmaxB) gives the lower bound, and Pr[X >= 1] the
// upper estimate used by the confidence.
#include "pair_probability.h"

namespace adb::detail {

PairEstimate estimateOverlapping(const CellCounts& counts, int depthA, int depthB, int maxDepthA,
                                 int maxDepthB) {
  PairEstimate e;
  e.overlap = true;
  e.s = counts.s;
  e.sA = counts.sA;
  e.sB = counts.sB;
  e.expected = counts.expected;
  if (e.sA == 0 || e.sB == 0) return e;  // no possible collision cell on one side: p = 0
  const double lb = cellIntersectionBound(depthA, depthB, maxDepthA, maxDepthB);
  const CollisionEstimate c = estimateCollision(e.s, e.sA, e.sB, lb);
  e.lower = c.lower;
  e.upper = c.upper;
  return e;
}

PairEstimate estimatePair(const TreeConstants& ta, std::uint32_t a, int depthA,
                          const TreeConstants& tb, std::uint32_t b, int depthB,
                          const RelativeFrame& frame) {
  PairKernel pair(*ta.tree, &a, 1, *tb.tree, &b, 1, frame);
  const unsigned mask = pair.overlapMask();
  if (mask == 0) return PairEstimate{};
  CellCounts counts[4];
  pair.cellCounts(mask, counts);
  return estimateOverlapping(counts[0], depthA, depthB, ta.maxDepth, tb.maxDepth);
}

bool nodesOverlap(const TreeConstants& ta, std::uint32_t a, const TreeConstants& tb,
                  std::uint32_t b, const RelativeFrame& frame) {
  return PairKernel(*ta.tree, &a, 1, *tb.tree, &b, 1, frame).overlapMask() != 0;
}

double pairFill(const TreeConstants& ta, std::uint32_t a, const TreeConstants& tb,
                std::uint32_t b, const RelativeFrame& frame) {
  PairKernel pair(*ta.tree, &a, 1, *tb.tree, &b, 1, frame);
  return pair.overlapMask() != 0 ? pair.occupiedFill(0, 0) : 0.0;
}

}  // namespace adb::detail
