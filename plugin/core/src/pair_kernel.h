// Internal: the pair kernel — the up to 2 x 2 child pairs of one expansion, tested together.
//
// An expansion of (A, B) tests each of A's two children against each of B's: four pairs over
// four boxes. The kernel poses each box once in the other tree's frame, with the two children
// of a node in the two lanes of one register (lanes.h), and runs a test for both children of B
// against one child of A in one instruction. It replaces a pair-at-a-time test (posing lazily,
// branching at every axis) for both traversal modes, and computes each value by the same
// expression in the same order, so every answer is the one the pair-at-a-time test gave, bit
// for bit (the reference in internal_tests/reference_child_pairs.h checks it).
//
// The tests, cheapest first: the two boxes on A's face axes (B's boxes are posed in A's frame
// for every pair anyway), on B's face axes, then each node's slab (NodeDistribution) against
// the other's box. A curved sheet's nodes are thin along their mean normal, so the
// slab rejects near misses the boxes cannot. The 9 edge-edge axes would prune a few more
// pairs at twice the cost. Touching counts as overlapping, within the frame's slack: a pair
// whose triangles could meet is never pruned.
//
// Pair (i, j), A's node i against B's node j, is index 2 i + j of every output.
#pragma once

#include <cstdint>

#include "adb/core/probability.h"
#include "adb/core/tree.h"
#include "lanes.h"
#include "relative_frame.h"

namespace adb::detail {

/// Up to two nodes of one tree (lane k holds node k; a single node fills both lanes), posed
/// for the other tree.
struct PosedNodes {
  Lanes c[3], h[3];            // box centre and half extents, own local frame
  Lanes cOther[3], hOther[3];  // centre and half extents of the box's AABB in the other frame
  Lanes normal[3];             // slab normal, own frame
  Lanes offset, halfWidth;     // slab: |normal . x - offset| <= halfWidth
  Lanes reach[3];              // |slab normal| along the other frame's axes: a box of half
                               // extents h' (other frame) reaches reach . h' along the normal
  const NodeDistribution* d[2];
  const Node* node[2];
  const NodeOccupancy* cells[2];  // occupancy (node_occupancy.h)
  int count;
};

/// The cell model's counts for one overlapping pair (pair_probability.h reads them).
struct CellCounts {
  int s = 0, sA = 0, sB = 0;  // common cells, and possible collision cells of each side
  double expected = 0.0;      // E[X] before rounding: rho_A rho_B s
};

class PairKernel {
 public:
  /// A's nodes ca[0..countA) against B's cb[0..countB), each count 1 or 2. Two nodes are
  /// siblings (ca[1] == ca[0] + 1), as an expansion's children are.
  PairKernel(const AdbTree& a, const std::uint32_t* ca, int countA, const AdbTree& b,
             const std::uint32_t* cb, int countB, const RelativeFrame& frame)
      : m_frame(frame) {
    loadBoxes(a, ca, countA, m_a);
    loadBoxes(b, cb, countB, m_b);
    const LaneFrame& f = frame.lanes;
    poseInOther(m_b, f.rBA, f.absBA, f.tBA);  // every pair's first test needs them
  }

  static constexpr int index(int i, int j) { return 2 * i + j; }

  /// Bit index(i, j) set where the pair is not proven apart by any test (see the file
  /// comment): the boxes and slabs, then the cells each node's triangles touch.
  unsigned overlapMask() {
    const unsigned mask = boxAndSlabMask();
    return mask & ~apartByCells(mask);
  }

  /// Bits of the pairs in `mask` whose nodes' occupied cells prove them apart: where the part
  /// of one node's box that the other's box (posed, grown by the slack) can reach holds no
  /// cell its triangles touch (node_occupancy.h). Not a distance: measure() leaves it out.
  unsigned apartByCells(unsigned mask) { return apartByCellsWithin(mask, 0.0); }
  /// The same with the region each node's posed box reaches in the other's frame shrunk by
  /// `shrink` (>= 0): a pair not reported apart keeps its cells meeting under any motion that
  /// moves no point by more than `shrink` (the posed box's faces move no further), which lets
  /// a traversal front certify the cell test together with the boxes' overlap.
  unsigned apartByCellsWithin(unsigned mask, double shrink) {
    if (mask == 0) return 0;
    mapA();
    return cellsApart(mask, m_frame.slack - shrink);
  }

  /// How full both nodes of pair (i, j) are where their boxes meet, in [0, 1]: the share of
  /// occupied cells (node_occupancy.h) in the part of A's node i that B's node j's posed box
  /// reaches, times the same share for B. Only for a pair overlapMask() reported (both frames
  /// are posed then). The evidence of a pair whose nodes the cell model cannot speak for.
  double occupiedFill(int i, int j) const;

  /// The pairs that the boxes and slabs leave overlapping: the tests that measure() turns
  /// into distances.
  unsigned boxAndSlabMask() {
    const Lanes slack = Lanes::all(m_frame.slack);
    const unsigned present = m_b.count == 2 ? 3u : 1u;
    // A's face axes: B's boxes in A's frame against A's node i.
    unsigned mask = ~apartOnFacesOfA<0>(slack) & present;
    if (m_a.count == 2) mask |= (~apartOnFacesOfA<1>(slack) & present) << 2;
    if (mask == 0) return 0;
    // B's face axes: A's node i in B's frame against B's boxes.
    mapA();
    if (mask & 3u) mask &= ~apartOnFacesOfB<0>(slack);
    if (mask & 12u) mask &= ~(apartOnFacesOfB<1>(slack) << 2);
    if (mask == 0) return 0;
    // Slabs: each node's slab against the other's box.
    slabs();
    if (mask & 3u) mask &= ~apartBySlabs<0>(slack);
    if (mask & 12u) mask &= ~(apartBySlabs<1>(slack) << 2);
    return mask;
  }

  /// Every test of overlapMask() measured instead of decided, per pair: the largest of the
  /// signed distances by which the face axes and slabs separate the two nodes (beyond the
  /// slack). > 0: apart by at least that much; <= 0: overlapping, each test short of
  /// separating by at least its magnitude. Under a rigid motion that moves no point of either
  /// node by more than d (each in the other's frame), a value changes by at most d: the
  /// certificate a traversal front keeps across steps. Returns overlapMask()'s answer, which
  /// agrees with the sign outside the slack (inside it the mask decides).
  unsigned measure(double separation[4]);
  /// How deeply the boxes of each pair overlapMask() reported overlap: >= 0, the smallest
  /// overlap along the six face axes (no test again). Only after overlapMask() reported one.
  void boxDepths(double depth[4]) const;
  /// The cell model's counts of each pair in `mask` (a subset of overlapMask()'s answer),
  /// from the intersection of the two boxes in both frames (pair_probability.cpp says how).
  void cellCounts(unsigned mask, CellCounts counts[4]) const {
    const CellsOfB b = cellsOfB();  // B's side, shared by both rows
    if (mask & 3u) countRow<0>(b, mask, counts);
    if (mask & 12u) countRow<1>(b, mask, counts);
  }
  /// overlapMask(), and cellCounts() of what it reports (ADB mode's expansion).
  unsigned overlapMaskAndCounts(CellCounts counts[4]) {
    const unsigned mask = overlapMask();
    if (mask != 0) cellCounts(mask, counts);
    return mask;
  }

 private:
  unsigned cellsApart(unsigned mask, double grow) const;
  void reachedBoxes(int i, int j, double grow, Vec3 inA[2], Vec3 inB[2]) const;

  // Boxes of nodes ids[0..count) (the last repeated in an unused lane) in their own frame:
  // centre and half extents in double, as Node::boxLo/boxHi give them.
  static void loadBoxes(const AdbTree& tree, const std::uint32_t* ids, int count,
                        PosedNodes& n) {
    const Node& n0 = tree.nodes()[ids[0]];
    const Node& n1 = tree.nodes()[ids[count - 1]];
    n.node[0] = &n0;
    n.node[1] = &n1;
    n.cells[0] = &tree.occupancy()[ids[0]];
    n.cells[1] = &tree.occupancy()[ids[count - 1]];
    Lanes first[4], last[4];  // lo x y z, hi x; then lo z, hi x y z
    loadFloatPairs(n0.lo, n1.lo, first);
    loadFloatPairs(n0.lo + 2, n1.lo + 2, last);
    const Lanes lo[3] = {first[0], first[1], first[2]};
    const Lanes hi[3] = {first[3], last[2], last[3]};
    const Lanes half = Lanes::all(0.5);
    for (int k = 0; k < 3; ++k) {
      n.c[k] = half * (hi[k] + lo[k]);
      n.h[k] = half * (hi[k] - lo[k]);
    }
    n.d[0] = &tree.distributions()[ids[0]];
    n.d[1] = &tree.distributions()[ids[count - 1]];
    n.count = count;
  }

  // x0 v0 + x1 v1 + x2 v2, summed left to right (as Eigen's dot and detail::mul sum).
  static Lanes dot(Lanes x0, Lanes x1, Lanes x2, const Lanes v[3]) {
    return x0 * v[0] + x1 * v[1] + x2 * v[2];
  }

  static void poseInOther(PosedNodes& n, const Lanes r[3][3], const Lanes absR[3][3],
                          const Lanes t[3]) {
    for (int row = 0; row < 3; ++row) {
      n.cOther[row] = dot(r[row][0], r[row][1], r[row][2], n.c) + t[row];
      n.hOther[row] = dot(absR[row][0], absR[row][1], absR[row][2], n.h);
    }
  }

  // The slab normals mapped by rOther's transpose (the inverse rotation: into the other
  // frame).
  static void slabsOf(PosedNodes& n, const Lanes rOther[3][3]) {
    Lanes slab[4];
    loadFloatPairs(n.d[0]->normal, n.d[1]->normal, slab);
    n.normal[0] = slab[0];
    n.normal[1] = slab[1];
    n.normal[2] = slab[2];
    n.offset = slab[3];
    n.halfWidth = Lanes::of(n.d[0]->halfWidth, n.d[1]->halfWidth);
    for (int row = 0; row < 3; ++row) {
      n.reach[row] = abs(dot(rOther[0][row], rOther[1][row], rOther[2][row], n.normal));
    }
  }

  // A's nodes in B's frame: only once a pair has passed A's face axes (most pairs do not).
  void mapA() {
    if (m_mappedA) return;
    const LaneFrame& f = m_frame.lanes;
    poseInOther(m_a, f.rAB, f.absAB, f.tAB);
    m_mappedA = true;
  }

  // A's slab normal is mapped into B's frame by rBA's transpose, B's by rAB's (each the
  // inverse of the other to the pose tolerance, as the pair-at-a-time test had them).
  void slabs() {
    if (m_slabs) return;
    slabsOf(m_a, m_frame.lanes.rBA);
    slabsOf(m_b, m_frame.lanes.rAB);
    m_slabs = true;
  }

  // Bits j of the pairs (I, j) that A's face axes prove apart.
  template <int I>
  unsigned apartOnFacesOfA(Lanes slack) const {
    LaneMask apart = abs(m_b.cOther[0] - m_a.c[0].broadcast(I)) >
                     (m_a.h[0].broadcast(I) + m_b.hOther[0]) + slack;
    for (int k = 1; k < 3; ++k) {
      apart = apart | (abs(m_b.cOther[k] - m_a.c[k].broadcast(I)) >
                       (m_a.h[k].broadcast(I) + m_b.hOther[k]) + slack);
    }
    return static_cast<unsigned>(apart.bits());
  }

  // Bits j of the pairs (I, j) that B's face axes prove apart.
  template <int I>
  unsigned apartOnFacesOfB(Lanes slack) const {
    LaneMask apart = abs(m_a.cOther[0].broadcast(I) - m_b.c[0]) >
                     (m_b.h[0] + m_a.hOther[0].broadcast(I)) + slack;
    for (int k = 1; k < 3; ++k) {
      apart = apart | (abs(m_a.cOther[k].broadcast(I) - m_b.c[k]) >
                       (m_b.h[k] + m_a.hOther[k].broadcast(I)) + slack);
    }
    return static_cast<unsigned>(apart.bits());
  }

  // Bits j of the pairs (I, j) that either node's slab proves apart from the other's box.
  template <int I>
  unsigned apartBySlabs(Lanes slack) const {
    return static_cast<unsigned>(
        ((slabOffsetOfA<I>() > slabReachOfA<I>() + slack) |
         (slabOffsetOfB<I>() > slabReachOfB<I>() + slack))
            .bits());
  }

  // How far B's box centres lie from A's node I's slab mid-plane, and the slab's half width
  // plus B's boxes' radii along its normal.
  template <int I>
  Lanes slabOffsetOfA() const {
    return abs(dot(m_a.normal[0].broadcast(I), m_a.normal[1].broadcast(I),
                   m_a.normal[2].broadcast(I), m_b.cOther) -
               m_a.offset.broadcast(I));
  }
  template <int I>
  Lanes slabReachOfA() const {
    return m_a.halfWidth.broadcast(I) + dot(m_a.reach[0].broadcast(I), m_a.reach[1].broadcast(I),
                                            m_a.reach[2].broadcast(I), m_b.h);
  }
  // The same for B's slabs against A's node I's box.
  template <int I>
  Lanes slabOffsetOfB() const {
    const Lanes centre[3] = {m_a.cOther[0].broadcast(I), m_a.cOther[1].broadcast(I),
                             m_a.cOther[2].broadcast(I)};
    return abs(dot(m_b.normal[0], m_b.normal[1], m_b.normal[2], centre) - m_b.offset);
  }
  template <int I>
  Lanes slabReachOfB() const {
    const Lanes half[3] = {m_a.h[0].broadcast(I), m_a.h[1].broadcast(I), m_a.h[2].broadcast(I)};
    return m_b.halfWidth + dot(m_b.reach[0], m_b.reach[1], m_b.reach[2], half);
  }

  // B's side of the cell counts, shared by both rows: its boxes' bounds in both frames and
  // its cells.
  struct CellsOfB {
    Lanes lo[3], hi[3];            // own frame
    Lanes loOther[3], hiOther[3];  // A's frame
    Lanes side, density, invSide;
  };
  CellsOfB cellsOfB() const {
    CellsOfB b;
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = m_b.c[k] - m_b.h[k];
      b.hi[k] = m_b.c[k] + m_b.h[k];
      b.loOther[k] = m_b.cOther[k] - m_b.hOther[k];
      b.hiOther[k] = m_b.cOther[k] + m_b.hOther[k];
    }
    Lanes cells[4];  // halfWidth, side, density, invSide
    loadFloatPairs(&m_b.d[0]->halfWidth, &m_b.d[1]->halfWidth, cells);
    b.side = cells[1];
    b.density = cells[2];
    b.invSide = cells[3];
    return b;
  }

  // round(x) for x >= 0 (truncating x + 0.5: without SSE4.1, floor would be a library call
  // per count), 0 for x <= 0 or NaN, at most `cap`.
  static Lanes roundCount(Lanes x, Lanes cap) {
    const Lanes rounded = truncated(min(x + Lanes::all(0.5), cap));
    return select(x > Lanes::all(0.0), rounded, Lanes::all(0.0));
  }

  // The counts of the pairs (I, j) in `mask` (pair_probability.cpp, steps 1 to 4).
  template <int I>
  void countRow(const CellsOfB& b, unsigned mask, CellCounts counts[4]) const {
    const Lanes one = Lanes::all(1.0);
    const NodeDistribution& da = *m_a.d[I];
    // The cell side is the coarser node's, per pair.
    const Lanes sideA = Lanes::all(da.side);
    const Lanes invA = Lanes::all(da.invSide);
    const LaneMask aCoarser = sideA >= b.side;
    const Lanes invCell = select(aCoarser, invA, b.invSide);
    // Cells touched by the boxes' intersection in A's frame and in B's, at least one per axis.
    Lanes inA{}, inB{};
    for (int k = 0; k < 3; ++k) {
      const Lanes ca = m_a.c[k].broadcast(I), ha = m_a.h[k].broadcast(I);
      const Lanes cao = m_a.cOther[k].broadcast(I), hao = m_a.hOther[k].broadcast(I);
      const Lanes extentA = min(ca + ha, b.hiOther[k]) - max(ca - ha, b.loOther[k]);
      const Lanes extentB = min(b.hi[k], cao + hao) - max(b.lo[k], cao - hao);
      const Lanes cellsA = max(extentA * invCell, one);
      const Lanes cellsB = max(extentB * invCell, one);
      inA = k == 0 ? cellsA : inA * cellsA;
      inB = k == 0 ? cellsB : inB * cellsB;
    }
    const Lanes touched = min(inA, inB);
    // The densities at the common cell size (step 3), then the counts.
    const Lanes densityA = Lanes::all(da.density);
    const Lanes rhoA = select(aCoarser, densityA, min(densityA * b.side * invA, one));
    const Lanes rhoB = select(aCoarser, min(b.density * sideA * b.invSide, one), b.density);
    const Lanes cap = Lanes::all(kMaxBins);
    const Lanes s = max(roundCount(touched, cap), one);
    const Lanes sA = min(s, roundCount(rhoA * s, cap));
    const Lanes sB = min(s, roundCount(rhoB * s, cap));
    const Lanes expected = rhoA * rhoB * s;
    int si[2], sAi[2], sBi[2];
    toInts(s, si);
    toInts(sA, sAi);
    toInts(sB, sBi);
    for (int j = 0; j < m_b.count; ++j) {
      const int p = index(I, j);
      if (((mask >> p) & 1u) == 0) continue;
      counts[p] = CellCounts{si[j], sAi[j], sBi[j], expected.lane(j)};
    }
  }

  template <int I>
  void measureRow(double slack, unsigned mask, double separation[4], unsigned& overlaps) const;

  const RelativeFrame& m_frame;
  PosedNodes m_a, m_b;
  bool m_mappedA = false, m_slabs = false;
};

}  // namespace adb::detail
