// The pair-at-a-time node test the pair kernel replaced (the code of commit 8374287,
// unchanged but for its namespace): the oracle the kernel must match bit for bit, masks,
// separations, depths and cell counts (test_pair_kernel.cpp).
#pragma once

#include <cstdint>

#include "adb/core/tree.h"
#include "pair_kernel.h"
#include "relative_frame.h"

namespace adb::reference {

using detail::mul;

/// A node ready to be tested against nodes of the other tree: its box in its own frame, and
/// its box and slab normal seen from the other tree's frame (filled by ChildPairs).
struct PosedNode {
  Vec3 c, h;                 // box centre and half extents, own local frame
  Vec3 cOther, hOther;       // centre and half extents of its box's AABB in the other frame
  Vec3 slabReach;            // |slab normal| along the other frame's axes: the radius of a box
                             // of half extents h' along the normal is slabReach . h'
  const NodeDistribution* d; // slab, cell side and density
};

/// overlap() and separation() of one pair, from one measure.
struct PairTest {
  bool overlaps;
  double separation;
};

/// The up to 2 x 2 child pairs of one expansion, posed lazily: B's children are mapped into
/// A's frame at once (every pair's first test needs them), an A child is mapped into B's
/// frame and a slab normal into the other frame only when a pair gets that far. Rejected
/// pairs cost what they did when each pair mapped its own boxes; surviving ones share the
/// work.
class ChildPairs {
 public:
  ChildPairs(const AdbTree& a, const std::uint32_t* ca, int countA, const AdbTree& b,
             const std::uint32_t* cb, int countB, const detail::RelativeFrame& frame);
  /// True unless A's child i and B's child j are proven apart: by a face axis of either box,
  /// or by either node's slab (NodeDistribution) against the other's box. Touching counts
  /// as overlapping (within frame.slack): the test never prunes a pair whose triangles
  /// could meet.
  bool overlap(int i, int j);
  /// overlap(), and for overlapping nodes how deeply their boxes overlap (>= 0: the smallest
  /// overlap along the six face axes); negative when they are apart.
  double overlapDepth(int i, int j);
  /// How deeply the boxes of a pair known to overlap (by overlap() or test()) overlap: >= 0,
  /// the smallest overlap along the six face axes. Does not test again.
  double boxDepth(int i, int j) const;
  /// Every test of overlap() measured instead of decided: the largest of the signed
  /// distances by which the face axes and slabs separate the two nodes (beyond the slack).
  /// > 0: apart by at least that much; <= 0: overlapping, each test short of separating by
  /// at least its magnitude. Under a rigid motion that moves no point of either node by more
  /// than d (each in the other's frame), the value changes by at most d: the certificate a
  /// traversal front keeps across steps.
  double separation(int i, int j);
  /// Both: overlap()'s answer (bit for bit) and separation(), for about the cost of the
  /// second.
  PairTest test(int i, int j);
  /// The posed nodes, complete once overlap(i, j) returned true.
  const PosedNode& a(int i) const { return m_a[i]; }
  const PosedNode& b(int j) const { return m_b[j]; }

 private:
  void mapA(int i);
  void reachA(int i);
  void reachB(int j);
  const detail::RelativeFrame& m_frame;
  Mat3 m_rBAt, m_rABt, m_absBA, m_absAB;  // the frame's, as the old RelativeFrame held them
  PosedNode m_a[2], m_b[2];
  bool m_mappedA[2] = {false, false};
  bool m_reachA[2] = {false, false}, m_reachB[2] = {false, false};
};

/// s, s_A, s_B and E[X] of a pair of overlapping posed nodes, as estimateOverlapping
/// computed them.
detail::CellCounts countsOverlapping(const PosedNode& a, const PosedNode& b);

}  // namespace adb::reference
