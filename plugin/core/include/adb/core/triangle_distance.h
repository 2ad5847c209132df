// triangleDistance: closest points of two separated triangles, for contacts that speculate
// (a pair within a contact margin before it touches) instead of waiting for the triangles to
// cross.
#pragma once

#include "adb/core/geometry.h"

namespace adb {

/// Result of triangleDistance: every field finite for finite input.
struct TriangleDistance {
  Vec3 pointOnA = Vec3::Zero();  ///< the point of A closest to B
  Vec3 pointOnB = Vec3::Zero();  ///< the point of B closest to A
  double distance = 0.0;         ///< |pointOnB - pointOnA|
};

/// The closest points of triangles (a0,a1,a2) and (b0,b1,b2), one frame. For triangles that
/// do not intersect the distance is attained by a vertex and the other triangle or by two
/// edges, so the result is the least of those 15 candidates: exact up to rounding. For
/// intersecting triangles it is the distance between their closest boundary features (not 0:
/// ask trianglesIntersect first). Degenerate triangles (repeated or collinear vertices) are
/// their edges and points. Non-finite input gives distance infinity and zero points. No
/// allocation, thread-safe (pure function).
TriangleDistance triangleDistance(const Vec3& a0, const Vec3& a1, const Vec3& a2,
                                  const Vec3& b0, const Vec3& b1, const Vec3& b2);

}  // namespace adb
