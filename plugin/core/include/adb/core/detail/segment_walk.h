// Internal to adb/core/ray_query.h: a segment prepared for slab tests against the tree's
// nodes. A header only because the query is a template over the caller's callback; not part
// of the API.
#pragma once

#include <algorithm>

#include "adb/core/geometry.h"
#include "adb/core/tree.h"

namespace adb {
struct SegmentQuery;
}

namespace adb::detail {

/// The segment in the tree's local frame, ready for slab tests. Built by prepareSegment.
struct PreparedSegment {
  Vec3 from = Vec3::Zero();     // local to the tree (mesh coordinates minus tree.origin())
  Vec3 inverse = Vec3::Zero();  // 1 / direction per axis; 1e300 on parallel axes
  Vec3 growLo = Vec3::Zero();   // subtracted from a node's lo: sweptHi + pad
  Vec3 growHi = Vec3::Zero();   // added to a node's hi: -sweptLo + pad
  double relativePad = 0.0;
  bool valid = false;
};

/// Checks the query (SegmentQueryStats::valid) and precomputes the inverse direction.
PreparedSegment prepareSegment(const AdbTree& tree, const SegmentQuery& query);

/// Whether the segment meets the node's grown box at a fraction in [0, maxFraction]; if so
/// `entry` is the first such fraction. Branch-free slabs: a parallel axis has a huge finite
/// inverse, so (lo - from) * inverse is +-huge outside the slab and never 0 * inf (NaN).
inline bool segmentEntry(const PreparedSegment& s, const Node& n, double maxFraction,
                         double& entry) {
  double pad = 0.0;
  if (s.relativePad > 0.0) {
    const float ex = std::max(n.hi[0] - n.lo[0], std::max(n.hi[1] - n.lo[1], n.hi[2] - n.lo[2]));
    pad = s.relativePad * static_cast<double>(ex);
  }
  double t0 = 0.0, t1 = maxFraction;
  for (int i = 0; i < 3; ++i) {
    const double lo = static_cast<double>(n.lo[i]) - s.growLo[i] - pad;
    const double hi = static_cast<double>(n.hi[i]) + s.growHi[i] + pad;
    const double a = (lo - s.from[i]) * s.inverse[i];
    const double b = (hi - s.from[i]) * s.inverse[i];
    t0 = std::max(t0, std::min(a, b));
    t1 = std::min(t1, std::max(a, b));
  }
  entry = t0;
  return t0 <= t1;
}

}  // namespace adb::detail
