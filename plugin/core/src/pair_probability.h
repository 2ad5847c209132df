// Internal: one node pair of two posed trees — the box overlap test and the parameters
// s, s_A, s_B of the probability model (paper §3.5; the [open] choices are documented at
// estimatePair and in docs/probability-model.md).
#pragma once

#include "adb/core/probability.h"
#include "adb/core/tree.h"

namespace adb::detail {

/// m * v, written out: Eigen leaves 3x3 * 3-vector products out of line at -O2, and this
/// is the traversal's inner loop.
inline Vec3 mul(const Mat3& m, const Vec3& v) {
  return Vec3(m(0, 0) * v[0] + m(0, 1) * v[1] + m(0, 2) * v[2],
              m(1, 0) * v[0] + m(1, 1) * v[1] + m(1, 2) * v[2],
              m(2, 0) * v[0] + m(2, 1) * v[1] + m(2, 2) * v[2]);
}

/// The relative placement of tree B in tree A's local frame, and the reverse, fixed for one
/// query. x_A = rBA * x_B + tBA.
struct RelativeFrame {
  Mat3 rBA, absBA;  // rotation B -> A and its element-wise absolute value
  Vec3 tBA;
  Mat3 rAB, absAB;  // A -> B: the true inverse of rBA (poses are orthonormal only to 1e-6,
  Vec3 tAB;         // so the transpose could misplace a box by more than the slack)
  Mat3 rBAt, rABt;  // transposes, for projecting a normal onto the other box's axes
  double slack = 0.0;  // absolute overlap tolerance: rounding of the transform, never less

  /// A point of B's local frame in A's local frame.
  Vec3 bToA(const Vec3& x) const { return mul(rBA, x) + tBA; }

  static RelativeFrame between(const AdbTree& a, const Pose& poseA, const AdbTree& b,
                               const Pose& poseB);
};

/// Per-tree constants the estimate reads.
struct TreeConstants {
  const AdbTree* tree;
  int maxDepth;
};

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
             const std::uint32_t* cb, int countB, const RelativeFrame& frame);
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
  const RelativeFrame& m_frame;
  PosedNode m_a[2], m_b[2];
  bool m_mappedA[2] = {false, false};
  bool m_reachA[2] = {false, false}, m_reachB[2] = {false, false};
};

struct PairEstimate {
  bool overlap = false;
  double lower = 0.0;  // Eq. 3: the priority and the acceptance test
  double upper = 0.0;  // Pr[X >= 1]
  double expected = 0.0;  // E[X] before rounding, uncapped (min(1, E[X]) bounds Pr[X >= 1])
  int s = 0, sA = 0, sB = 0;
};

/// The probability of a pair of overlapping posed nodes at the given depths (overlap is set).
PairEstimate estimateOverlapping(const PosedNode& a, int depthA, const PosedNode& b, int depthB,
                                 int maxDepthA, int maxDepthB);

/// Overlap test plus, when they overlap, the probability of one pair given by index.
PairEstimate estimatePair(const TreeConstants& ta, std::uint32_t a, int depthA,
                          const TreeConstants& tb, std::uint32_t b, int depthB,
                          const RelativeFrame& frame);
bool nodesOverlap(const TreeConstants& ta, std::uint32_t a, const TreeConstants& tb,
                  std::uint32_t b, const RelativeFrame& frame);

}  // namespace adb::detail
