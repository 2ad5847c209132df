// Internal: the traversal front an exact-mode query keeps across steps (temporal coherence).
//
// A query with QuerySettings::keepFront records every node pair its depth-first descent
// evaluated, in the order it processed them (pre-order: a pair, then everything below it),
// each with a *certificate*: how far its boxes and slabs were apart (> 0), or how deeply
// every one of those tests overlapped (< 0), at a reference pose of the two trees. Under a
// rigid motion that moves no point of either tree by more than d (each seen from the other's
// frame), every test's value changes by at most d (PairKernel::measure): a pair whose
// certificate exceeds d has the answer it had, without a test. The next query walks the
// recorded pairs in the same order and tests only those whose certificate the motion has
// used up; it descends afresh where a pair that was apart now overlaps and drops what lies
// below a pair that came apart, so what it visits and finds is what a descent from the roots
// would, in the same order (same witnesses), for the tests of the pairs that changed. This
// is Ehmann and Lin's front tracking with Weller and Zachmann's idea of separation
// certificates, applied to every evaluated pair, not only to the separated ones, so that
// even the pairs above the contacts are not re-tested while the bodies rest.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "adb/core/geometry.h"
#include "adb/core/tree.h"
#include "pair_probability.h"

namespace adb::detail {

/// One evaluated node pair: 16 bytes. The entries below it (its subtree, pre-order) follow
/// it; `below` counts them, so that a walk steps over a subtree at once.
struct FrontEntry {
  std::uint32_t a, b;      // node indices in tree A and tree B
  float certificate;       // > 0 apart by it, < 0 overlapping by it, 0 unknown: re-test
  std::uint8_t depthA, depthB;
  std::uint16_t below;     // entries of its subtree (< kMaxFrontEntries)
  bool apart(double motion) const { return certificate > motion; }
  bool overlapping(double motion) const { return -certificate > motion; }
};
static_assert(sizeof(FrontEntry) == 16, "FrontEntry is 16 bytes");

/// A front's entries hold fewer pairs than this (16 bytes each, two buffers: 2 MiB per
/// pair of trees at most). A descent that evaluates more records nothing further and the
/// next query starts from the roots: such a pair is not resting.
inline constexpr std::size_t kMaxFrontEntries = std::size_t{1} << 16;
/// Trees deeper than this (a depth must fit FrontEntry's byte) keep no front.
inline constexpr int kMaxFrontDepth = 255;

/// A certificate in float, rounded towards zero so that it never claims more than it
/// measured. Values within the rounding of the test are unknown (0).
inline float certificateOf(double separation) {
  float c = static_cast<float>(separation);
  if (std::abs(static_cast<double>(c)) > std::abs(separation)) c = std::nextafter(c, 0.0f);
  return std::isfinite(c) ? c : 0.0f;
}

/// The pose of B relative to A (and back) at which a front's certificates hold, and the
/// bound on how far any point of either tree has moved since, seen from the other.
struct FrontReference {
  Mat3 rBA = Mat3::Identity(), rAB = Mat3::Identity();
  Vec3 tBA = Vec3::Zero(), tAB = Vec3::Zero();

  static FrontReference of(const RelativeFrame& frame) {
    FrontReference r;
    r.rBA = frame.rBA;
    r.rAB = frame.rAB;
    r.tBA = frame.tBA;
    r.tAB = frame.tAB;
    return r;
  }

  /// |t' - t| + |R' - R|_F r for a point at distance r from its tree's local origin, the
  /// larger of the two directions, plus the frame's slack (rounding of the transforms).
  double motion(const RelativeFrame& now, double radiusA, double radiusB) const {
    const double bInA = (now.tBA - tBA).norm() + (now.rBA - rBA).norm() * radiusB;
    const double aInB = (now.tAB - tAB).norm() + (now.rAB - rAB).norm() * radiusA;
    return std::max(bInA, aInB) + now.slack;
  }
};

/// How far the farthest point of a tree's boxes lies from its local origin.
inline double treeRadius(const AdbTree& tree) {
  const Node& root = tree.root();
  return root.boxLo().cwiseAbs().cwiseMax(root.boxHi().cwiseAbs()).norm();
}

/// Takes `consumed` off every certificate's magnitude (what moving the reference pose used
/// up; see Traversal's `consumed`), leaving 0 where nothing is left.
inline void settleConsumed(std::vector<FrontEntry>& entries, double consumed) {
  for (FrontEntry& e : entries) {
    const double c = e.certificate;
    const double left = std::abs(c) - consumed;
    e.certificate = left > 0.0 ? certificateOf(c > 0.0 ? left : -left) : 0.0f;
  }
}

}  // namespace adb::detail
