// Internal: closest points of two closed 3D segments, shared by the triangle test (distance
// of degenerate triangles) and the triangle contact (edge-edge contacts).
#pragma once

#include "adb/core/geometry.h"

namespace adb::detail {

/// Closest points c1 on p1q1 and c2 on p2q2 (Ericson, Real-Time Collision Detection 5.1.9).
/// Every division guarded: points, parallel and degenerate segments included; inf quotients
/// are clamped, never NaN.
inline void closestSegmentPoints(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2,
                                 Vec3& c1, Vec3& c2) {
  const auto clamp01 = [](double x) { return x < 0 ? 0.0 : (x > 1 ? 1.0 : x); };
  const Vec3 d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0, t = 0;
  if (a <= 0 && e <= 0) {
    // both points
  } else if (a <= 0) {
    t = clamp01(f / e);
  } else {
    const double c = d1.dot(r);
    if (e <= 0) {
      s = clamp01(-c / a);
    } else {
      const double b = d1.dot(d2);
      const double denom = a * e - b * b;
      // Parallel (denom 0, or negative by rounding): any s works, start at 0 and let the
      // clamping below pick the closest pair.
      s = denom > 0 ? clamp01((b * f - c * e) / denom) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = clamp01(-c / a);
      } else if (t > 1) {
        t = 1;
        s = clamp01((b - c) / a);
      }
    }
  }
  c1 = p1 + s * d1;
  c2 = p2 + t * d2;
}

}  // namespace adb::detail
