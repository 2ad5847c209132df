// trianglesIntersect: the exact (tolerant, conservative) triangle-triangle test at the leaves of
// the ADB-tree traversal, and its tolerance constant.
//
// Design (details and the reasoning behind each threshold are in triangle_test.cpp):
//  1. Translate so that a0 is the origin; the scale L is the largest extent of the six
//     vertices' axis-aligned bounding box (symmetric in the two triangles and in vertex order,
//     unlike "largest coordinate after translation", so swapping arguments never changes the
//     tolerance). Extreme scales (and L == 0) are normalised by an exact power of two.
//  2. Fast rejection (the common case, no division): signed plane values of b's vertices
//     against a's plane, then of a's against b's. All three strictly beyond the zero band on
//     one side means no contact. The zero band is max(eps * |n|, rounding-error bound of the
//     computed value), eps = kTriangleTestRelativeTolerance * L, so a computed sign is either
//     the exact sign or zero, even for slivers whose normal is mostly rounding noise.
//  3. All six plane values strictly non-zero (general position): Guigue-Devillers, two more
//     orientation predicates, each trusted only beyond max(error bound, eps band); a decision
//     there is exact, anything unsure goes on to step 4.
//  4. Otherwise the complete rule: two closed triangles meet iff an edge of one meets the
//     other. Segment vs triangle: clip the segment to a slab of half-width 2 * band around the
//     plane, project segment and triangle onto the plane dropping the normal's dominant axis,
//     and run a 2D separating-axis test (3 triangle edges + the segment's line) in which values
//     within eps are treated as touching. Coplanar input is the special case "whole segment in
//     the slab"; no intersection point is ever computed from an ill-conditioned division.
//  5. A triangle whose smallest height is <= eps is degenerate and is replaced by its longest
//     edge (a point when all three vertices coincide): segment vs triangle as in step 4, or
//     the closest distance between two segments (Ericson) <= eps.
// Consequences: no false negatives for the translated input (every tolerance only ever turns
// "separated" into "touching" or "unsure"); false positives only for pairs within a few eps
// of each other (for slivers, within the rounding band of their plane, about
// 1e-15 L / sin(smallest angle)).
#pragma once

#include "adb/core/geometry.h"

namespace adb {

/// Relative tolerance of trianglesIntersect: distances below this times the configuration's
/// scale (see trianglesIntersect) count as zero.
inline constexpr double kTriangleTestRelativeTolerance = 1e-12;

/// True when the two closed triangles share at least one point. Touching (a vertex, an edge
/// or a face of one lying on the other) and coplanar overlapping triangles count as
/// intersecting. Degenerate triangles (zero area: repeated or collinear vertices) are treated
/// as the segment or point they are; a triangle counts as degenerate when its smallest height
/// is at most eps. Distances (to a plane, to an edge line, between segments) whose magnitude is
/// below eps = kTriangleTestRelativeTolerance * L are snapped to zero, where L is the largest
/// extent along x, y or z of the bounding box of all six vertices; touching configurations
/// decided in floating point are therefore stable, and neither L nor the decision depends on
/// the argument or vertex order (except by rounding, for inputs right at the edge of the
/// tolerance band). Conservative: never misses a true intersection of the input as translated
/// to a0 (that subtraction rounds to half an ulp of the coordinates); reports contact for
/// disjoint triangles only within a few eps (more for extreme slivers, see the file comment).
/// Power-of-two scalings of the input give the same answers. Non-finite coordinates give
/// false. Never reads out of bounds, never produces NaN, no allocation. Thread-safe (pure
/// function).
bool trianglesIntersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                        const Vec3& b1, const Vec3& b2);

}  // namespace adb
