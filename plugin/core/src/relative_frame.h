// Internal: where tree B lies in tree A's frame and back, fixed for one query.
#pragma once

#include "adb/core/geometry.h"
#include "adb/core/tree.h"
#include "lanes.h"

namespace adb::detail {

/// m * v, written out: Eigen leaves 3x3 * 3-vector products out of line at -O2, and this
/// is the traversal's inner loop.
inline Vec3 mul(const Mat3& m, const Vec3& v) {
  return Vec3(m(0, 0) * v[0] + m(0, 1) * v[1] + m(0, 2) * v[2],
              m(1, 0) * v[0] + m(1, 1) * v[1] + m(1, 2) * v[2],
              m(2, 0) * v[0] + m(2, 1) * v[1] + m(2, 2) * v[2]);
}

/// The frame's matrices with every entry in both lanes, for the pair kernel: built once per
/// query, so that an expansion loads them instead of broadcasting 48 numbers.
struct LaneFrame {
  Lanes rBA[3][3], absBA[3][3], tBA[3];
  Lanes rAB[3][3], absAB[3][3], tAB[3];
};

/// The relative placement of tree B in tree A's local frame, and the reverse, fixed for one
/// query. x_A = rBA * x_B + tBA.
struct RelativeFrame {
  Mat3 rBA;  // rotation B -> A (its element-wise absolute value is in `lanes` only)
  Vec3 tBA;
  Mat3 rAB;  // A -> B: the true inverse of rBA (poses are orthonormal only to 1e-6,
  Vec3 tAB;  // so the transpose could misplace a box by more than the slack)
  double slack = 0.0;  // absolute overlap tolerance: rounding of the transform, never less
  LaneFrame lanes;     // the above, broadcast

  /// A point of B's local frame in A's local frame.
  Vec3 bToA(const Vec3& x) const { return mul(rBA, x) + tBA; }

  static RelativeFrame between(const AdbTree& a, const Pose& poseA, const AdbTree& b,
                               const Pose& poseB);
};

}  // namespace adb::detail
