// Segment queries through an ADB-tree: the checks and set-up behind
// forEachTriangleAlongSegment (the traversal itself is a template in ray_query.h).
#include "adb/core/ray_query.h"

#include <cmath>

namespace adb::detail {
namespace {

// Stands for 1 / 0. A product (lo - from) * inverse may overflow to +-inf but is never NaN:
// the factor in brackets is never NaN (finite inputs, growth finite) and the inverse is
// finite and nonzero.
constexpr double kParallelInverse = 1e300;

}  // namespace

PreparedSegment prepareSegment(const AdbTree& tree, const SegmentQuery& q) {
  PreparedSegment s;
  // Refuse, rather than guess at, anything that would put a NaN into the slab tests.
  if (!q.from.allFinite() || !q.to.allFinite() || !q.sweptLo.allFinite() ||
      !q.sweptHi.allFinite() || (q.sweptLo.array() > q.sweptHi.array()).any() ||
      !std::isfinite(q.pad) || !std::isfinite(q.relativePad) || q.pad < 0.0 ||
      q.relativePad < 0.0) {
    return s;
  }
  s.from = q.from - tree.origin();
  const Vec3 d = q.to - q.from;
  if (!s.from.allFinite() || !d.allFinite()) return s;  // overflow near the double range
  for (int i = 0; i < 3; ++i) {
    // Parallel when 1 / d overflows (d is 0 or subnormal). The huge finite stand-in makes a
    // point outside the slab enter at +-1e300 (never) and one inside at no constraint: the
    // same answers as a branch, without one per node. The error is below 1e-300 units.
    const double inv = d[i] != 0.0 ? 1.0 / d[i] : kParallelInverse;
    s.inverse[i] = std::isfinite(inv) && std::abs(inv) < kParallelInverse ? inv : kParallelInverse;
  }
  s.growLo = q.sweptHi + Vec3::Constant(q.pad);
  s.growHi = -q.sweptLo + Vec3::Constant(q.pad);
  s.relativePad = q.relativePad;
  s.valid = s.growLo.allFinite() && s.growHi.allFinite();
  return s;
}

}  // namespace adb::detail
