// triangleDistance: the least of the 15 vertex-triangle and edge-edge candidates.
#include "adb/core/triangle_distance.h"

#include <cmath>
#include <limits>

#include "adb/core/primitive_contact.h"
#include "segment_closest_points.h"

namespace adb {
namespace {

struct Best {
  TriangleDistance d;
  double squared = std::numeric_limits<double>::infinity();
  void offer(const Vec3& onA, const Vec3& onB) {
    const double s = (onB - onA).squaredNorm();
    if (s < squared) {
      squared = s;
      d.pointOnA = onA;
      d.pointOnB = onB;
    }
  }
};

}  // namespace

TriangleDistance triangleDistance(const Vec3& a0, const Vec3& a1, const Vec3& a2,
                                  const Vec3& b0, const Vec3& b1, const Vec3& b2) {
  const Vec3 a[3] = {a0, a1, a2};
  const Vec3 b[3] = {b0, b1, b2};
  for (const Vec3& v : a) {
    if (!v.allFinite()) return {Vec3::Zero(), Vec3::Zero(), std::numeric_limits<double>::infinity()};
  }
  for (const Vec3& v : b) {
    if (!v.allFinite()) return {Vec3::Zero(), Vec3::Zero(), std::numeric_limits<double>::infinity()};
  }
  Best best;
  // Vertex against face: closestPointOnTriangle handles degenerate faces (their edges).
  for (const Vec3& v : a) best.offer(v, closestPointOnTriangle(v, b0, b1, b2));
  for (const Vec3& v : b) best.offer(closestPointOnTriangle(v, a0, a1, a2), v);
  // Edge against edge: where two edges pass closest to each other inside both triangles'
  // boundaries (the only other place a minimum of separated triangles can be).
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      Vec3 onA, onB;
      detail::closestSegmentPoints(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3], onA, onB);
      best.offer(onA, onB);
    }
  }
  best.d.distance = std::sqrt(best.squared);
  return best.d;
}

}  // namespace adb
