// triangleContact: contact point, normal and penetration depth of two intersecting triangles,
// for rigid-body response (the Bullet plugin turns it into a manifold point).
//
// Method (details and the reasons for every constant are in triangle_contact.cpp):
//  1. Candidate axes are the Minkowski-difference facet normals of the two triangles: A's face
//     normal, B's face normal and the nine edge-edge cross products. For convex polytopes the
//     penetration depth (minimum translation distance) is attained along one of them, so
//     taking the smallest overlap over this set is the exact penetration depth, not a
//     heuristic. Axes whose direction would be dominated by rounding (sliver or zero-area
//     triangles, short or parallel edges) are skipped; a degenerate triangle therefore
//     contributes its edges only and the other triangle's normal is used.
//  2. Both orientations of every axis are candidates and the depth of "move B along +d" is
//     max(A.d) - min(B.d). With a hint, an axis that is clearly not perpendicular to it keeps
//     only the orientation that agrees with the hint (so a deep penetration is never resolved
//     through the other body); without a hint it is the plain minimum translation.
//  3. Stability: edge-edge axes compete with a 5 % handicap (ODE's fudge factor), and among
//     candidates within a small tie band of the best one the choice is face over edge, then
//     the one best aligned with the hint, then the larger triangle, then the winding's own
//     orientation. None of these keys is a rounding-level quantity, so resting contact does
//     not flicker between equivalent normals.
//  4. Contact point: for a face normal, the other triangle is clipped to the face's prism and
//     the deepest part of what is left (a weighted mean over a thin band) is taken; for an edge
//     axis, the closest points of the two supporting features. pointOnB lies in B, and
//     pointOnB + depth * normal is (up to the averaging band) the matching point on A.
#pragma once

#include "adb/core/geometry.h"

namespace adb {

/// Result of triangleContact. For valid == false: normal and depth are zero and pointOnB is
/// B's centroid (the origin for non-finite input); every field is finite either way.
struct TriangleContact {
  Vec3 pointOnB = Vec3::Zero();  ///< a point on (or in) triangle B at the contact
  Vec3 normal = Vec3::Zero();    ///< unit, from A towards B: B moves along +normal to separate
  double depth = 0.0;            ///< penetration depth >= 0 along normal (0 for touching)
  bool valid = false;            ///< false only when the input defines no contact direction
};

/// Contact between two intersecting triangles (a0,a1,a2) and (b0,b1,b2) in one frame.
///
/// `depth` is the overlap of the two triangles' projections onto `normal`: translating B by
/// (depth + any positive margin) * normal separates them. Without a hint, `normal` is the
/// minimum-translation direction (up to the stability rules in the file comment); ties are
/// broken towards face normals and, among equal faces, the larger triangle's winding (A's
/// +normal, or B's -normal). `hintNormal` is an optional preferred separation direction from A
/// to B (the previous frame's normal, or the direction between the bodies' centres); any
/// length, zero (or non-finite) for none. It fixes the orientation of every axis that is more
/// than ~0.6 degrees from perpendicular to it and decides between (near-)equally deep faces.
///
/// Degenerate triangles (zero area, below a relative height of 1e-9 of the configuration) are
/// treated as their edges. When both are degenerate and no edge pair defines an axis
/// (parallel segments, points): the direction between their closest points if that is above
/// rounding, else the hint, else valid = false. Non-finite coordinates give valid = false.
/// The triangles are assumed to intersect (trianglesIntersect); for a separated pair the
/// result is the most separating candidate axis with depth 0.
///
/// Invariant (up to rounding) under translation, exact under power-of-two scaling (depth and
/// point scale along), negates normal and keeps depth when A and B (and the hint's sign) are
/// swapped, except for exact ties in area. No allocation, no NaN, thread-safe (pure function).
TriangleContact triangleContact(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                                const Vec3& b1, const Vec3& b2, const Vec3& hintNormal);

}  // namespace adb
