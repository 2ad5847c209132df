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

#include <algorithm>
#include <cmath>


namespace adb::detail {
namespace {

// Transform-rounding tolerance of the overlap test, relative to the scene's magnitude.
constexpr double kOverlapRelativeSlack = 1e-12;

// One box seen from the other's frame: the AABB (centre c, half extent h) of the mapped box.
struct MappedBox {
  Vec3 c, h;
};

struct BoxPair {
  Vec3 cA, hA, cB, hB;  // each box in its own frame
  MappedBox bInA, aInB;
};

// Maps the boxes into each other's frame and tests the 6 face axes of the separating-axis
// test on the way: B's box on A's axes first, and only if that overlaps, A's box on B's axes.
// The 9 edge-edge axes would prune a few more pairs at twice the cost.
bool mapAndTest(const Node& a, const Node& b, const RelativeFrame& f, BoxPair& p) {
  p.cA = 0.5 * (a.boxHi() + a.boxLo());
  p.hA = 0.5 * (a.boxHi() - a.boxLo());
  p.cB = 0.5 * (b.boxHi() + b.boxLo());
  p.hB = 0.5 * (b.boxHi() - b.boxLo());
  p.bInA = {mul(f.rBA, p.cB) + f.tBA, mul(f.absBA, p.hB)};
  const Vec3 dA = (p.bInA.c - p.cA).cwiseAbs();
  if ((dA.array() > (p.hA + p.bInA.h).array() + f.slack).any()) return false;
  p.aInB = {mul(f.rAB, p.cA) + f.tAB, mul(f.absAB, p.hA)};
  const Vec3 dB = (p.aInB.c - p.cB).cwiseAbs();
  return !(dB.array() > (p.hB + p.aInB.h).array() + f.slack).any();
}

// The other node's box (centre `c` already in this node's frame, half extents `h` along its
// own axes, `otherToThisT` the transpose of the map from its frame into this one) against this
// node's slab.
bool slabOverlaps(const NodeDistribution& d, const Vec3& c, const Vec3& h,
                  const Mat3& otherToThisT, double slack) {
  const Vec3 n(d.normal[0], d.normal[1], d.normal[2]);
  // The box's radius along n: sum over its axes of |n . mapped axis| * half extent.
  const double radius = mul(otherToThisT, n).cwiseAbs().dot(h);
  return std::abs(n.dot(c) - d.offset) <= d.halfWidth + radius + slack;
}

// Boxes, then slabs: a curved sheet's nodes are thin along their mean normal, so the slab
// rejects near misses the boxes cannot (measured in docs/core-results.md).
bool mapAndTestAll(const TreeConstants& ta, std::uint32_t ia, const TreeConstants& tb,
                   std::uint32_t ib, const RelativeFrame& f, BoxPair& p) {
  if (!mapAndTest(ta.tree->nodes()[ia], tb.tree->nodes()[ib], f, p)) return false;
  return slabOverlaps(ta.tree->distributions()[ia], p.bInA.c, p.hB, f.rBAt, f.slack) &&
         slabOverlaps(tb.tree->distributions()[ib], p.aInB.c, p.hA, f.rABt, f.slack);
}

// Cells of side `cell` touched by the intersection of box (c, h) with a mapped box; at least
// one per axis.
double touchedCells(const Vec3& c, const Vec3& h, const MappedBox& other, double cell) {
  const Vec3 lo = (c - h).cwiseMax(other.c - other.h);
  const Vec3 hi = (c + h).cwiseMin(other.c + other.h);
  return ((hi - lo) / cell).cwiseMax(Vec3::Ones()).prod();
}

int roundCount(double x, int cap) {
  // x is finite and >= 0 by construction; the clamp keeps a corrupt value from overflowing.
  if (!(x > 0.0)) return 0;
  return static_cast<int>(std::min(std::floor(x + 0.5), static_cast<double>(cap)));
}

}  // namespace

RelativeFrame RelativeFrame::between(const AdbTree& a, const Pose& poseA, const AdbTree& b,
                                     const Pose& poseB) {
  // World placement of each tree's local frame: world = R x_local + (R origin + t).
  const Vec3 ta = poseA.rotation * a.origin() + poseA.translation;
  const Vec3 tb = poseB.rotation * b.origin() + poseB.translation;
  RelativeFrame f;
  // world -> A is the inverse of A's rotation; exact inverses keep the frame consistent for
  // rotations that are orthonormal only to the pose tolerance.
  const Mat3 worldToA = poseA.rotation.inverse();
  f.rBA = worldToA * poseB.rotation;
  f.tBA = worldToA * (tb - ta);
  f.rAB = f.rBA.inverse();
  f.tAB = -(f.rAB * f.tBA);
  f.absBA = f.rBA.cwiseAbs();
  f.absAB = f.rAB.cwiseAbs();
  f.rBAt = f.rBA.transpose();
  f.rABt = f.rAB.transpose();
  const auto radius = [](const Node& n) {
    return std::max(n.boxLo().cwiseAbs().maxCoeff(), n.boxHi().cwiseAbs().maxCoeff());
  };
  f.slack = kOverlapRelativeSlack * (f.tBA.norm() + radius(a.root()) + radius(b.root()));
  return f;
}

bool nodesOverlap(const TreeConstants& ta, std::uint32_t ia, const TreeConstants& tb,
                  std::uint32_t ib, const RelativeFrame& f) {
  BoxPair boxes;
  return mapAndTestAll(ta, ia, tb, ib, f, boxes);
}

double overlapDepth(const TreeConstants& ta, std::uint32_t ia, const TreeConstants& tb,
                    std::uint32_t ib, const RelativeFrame& f) {
  BoxPair p;
  if (!mapAndTestAll(ta, ia, tb, ib, f, p)) return -1.0;
  // The boxes' overlap along each of the six face axes; the smallest is how far they would
  // have to move apart along a face axis.
  const Vec3 inA = p.hA + p.bInA.h - (p.bInA.c - p.cA).cwiseAbs();
  const Vec3 inB = p.hB + p.aInB.h - (p.aInB.c - p.cB).cwiseAbs();
  return std::max(0.0, std::min(inA.minCoeff(), inB.minCoeff()));
}

PairEstimate estimatePair(const TreeConstants& ta, std::uint32_t ia, int depthA,
                          const TreeConstants& tb, std::uint32_t ib, int depthB,
                          const RelativeFrame& f) {
  PairEstimate e;
  BoxPair boxes;
  if (!mapAndTestAll(ta, ia, tb, ib, f, boxes)) return e;
  e.overlap = true;

  const NodeDistribution& cellsA = ta.tree->distributions()[ia];
  const NodeDistribution& cellsB = tb.tree->distributions()[ib];
  const double cell = std::max(cellsA.side, cellsB.side);  // > 0: sides are floored
  const double touched = std::min(touchedCells(boxes.cA, boxes.hA, boxes.bInA, cell),
                                  touchedCells(boxes.cB, boxes.hB, boxes.aInB, cell));
  e.s = std::max(1, roundCount(touched, kMaxBins));
  const double rhoA = std::min(1.0, cellsA.density * (cell / cellsA.side));
  const double rhoB = std::min(1.0, cellsB.density * (cell / cellsB.side));
  e.sA = std::min(e.s, roundCount(rhoA * e.s, kMaxBins));
  e.sB = std::min(e.s, roundCount(rhoB * e.s, kMaxBins));
  // E[X] = v w / u before rounding: a pair that rounding prunes (s_A or s_B = 0) keeps this
  // much doubt in the confidence (Markov: Pr[X >= 1] <= E[X]).
  e.expected = std::min(1.0, rhoA * rhoB * e.s);
  if (e.sA == 0 || e.sB == 0) return e;  // no possible collision cell on one side: p = 0
  const double lb = cellIntersectionBound(depthA, depthB, ta.maxDepth, tb.maxDepth);
  const CollisionEstimate c = estimateCollision(e.s, e.sA, e.sB, lb);
  e.lower = c.lower;
  e.upper = c.upper;
  return e;
}

}  // namespace adb::detail
