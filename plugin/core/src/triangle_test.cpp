// trianglesIntersect: plane rejection, Guigue-Devillers for general position, and for
// everything near a touching, coplanar or degenerate configuration the complete rule "some
// edge meets the other triangle" (slab clip + tolerant 2D separating axes); degenerate
// triangles as segments or points.
//
// Why it cannot miss a contact (for the input translated to a0): every decision is a sign
// test "value > band", "value < -band" or "otherwise zero/unsure", where band is at least the
// rounding-error bound of the computed value. So a computed sign is the exact sign or zero;
// in the complete rule zero means "touching", which only ever moves an answer towards
// "intersecting", and Guigue-Devillers hands every unsure case to the complete rule. The 2D
// values of the complete rule need no error term: their coordinates are bounded by L, so their
// rounding error (~1e-15 L |edge|) is far below the eps * |edge| tolerance.
#include "adb/core/triangle_test.h"

#include "segment_closest_points.h"

#include <cmath>
#include <utility>

namespace adb {
namespace {

using Vec2 = Eigen::Vector2d;

constexpr double kUnitRoundoff = 0x1p-53;

// Bound on |computed - exact| of a plane value n.x with n = u x v, in units of
// L * crossAbsSum(u, v): about 8u for the worst case (differences rounded before the cross
// product, cross product, difference x = w - v0 rounded, dot product); 16u leaves room for the
// second-order terms. It only matters for slivers: otherwise eps * |n| is far larger.
constexpr double kPlaneErrorFactor = 16 * kUnitRoundoff;

// Configurations whose scale L lies in this range are used as translated. All products in the
// test have degree <= 4 in the coordinates, so 2^(+-200) keeps them far from overflow and from
// the subnormal range; outside it the coordinates are rescaled by an exact power of two.
constexpr double kMinUnscaledExtent = 0x1p-200;
constexpr double kMaxUnscaledExtent = 0x1p+200;

// By-value min/max: they compile to minsd/maxsd. std::min/std::max take references, and
// with temporaries GCC -O2 emitted stack round trips and data-dependent branches (which
// mispredict on random input) in the hot path.
inline double minOf(double a, double b) { return b < a ? b : a; }
inline double maxOf(double a, double b) { return a < b ? b : a; }

/// Sum of the absolute values of the six products in u x v: the magnitude that scales the
/// rounding error of the computed cross product.
inline double crossAbsSum(const Vec3& u, const Vec3& v) {
  return std::abs(u.y() * v.z()) + std::abs(u.z() * v.y()) + std::abs(u.z() * v.x()) +
         std::abs(u.x() * v.z()) + std::abs(u.x() * v.y()) + std::abs(u.y() * v.x());
}

/// Zero band for plane values n.(x - v0): the eps distance, raised to the rounding-error bound.
inline double planeBand(const Vec3& n, double eps, double scale, double absSum) {
  return maxOf(eps * n.norm(), kPlaneErrorFactor * scale * absSum);
}

/// True when all three plane values are strictly beyond the band on the same side.
inline bool allOnOneSide(double d0, double d1, double d2, double band) {
  return minOf(d0, minOf(d1, d2)) > band || maxOf(d0, maxOf(d1, d2)) < -band;
}

inline double cross2(const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); }

// ---- General position: Guigue-Devillers ---------------------------------------------------
//
// When every vertex is strictly off the other triangle's plane (beyond its band), the
// Guigue-Devillers test decides with two orientation predicates on the input points, no
// division. Each predicate's sign is trusted only beyond max(its rounding-error bound, an eps
// band), so a decision taken here is the exact answer for the translated input and never
// overrides a touching configuration; anything closer goes to the complete rule below.

// Rounding-error bound factor of a 3x3 determinant of coordinate differences against its
// permanent: Shewchuk's orient3d bound (7 + 56u) u, rounded up.
constexpr double kOrientErrorFactor = 8 * kUnitRoundoff;

enum class Verdict { Disjoint, Intersect, Unsure };

/// Sign of det[b - a, c - a, d - a] (6 x the signed volume of abcd) when it lies beyond both
/// its rounding-error bound and eps * |e1|_1 * |e2|_1, else 0. e1, e2 are the directions of
/// the two opposite edges of abcd whose lines the predicate compares: |det| = |e1 x e2| *
/// distance(lines) <= |e1|_1 |e2|_1 * distance, so a decided sign means the lines are more
/// than eps apart.
int decidedOrientation(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d, const Vec3& e1,
                       const Vec3& e2, double eps) {
  const Vec3 u = b - a, v = c - a, w = d - a;
  const double det = u.cross(v).dot(w);
  const double permanent = std::abs(w.x()) * (std::abs(u.y() * v.z()) + std::abs(u.z() * v.y())) +
                           std::abs(w.y()) * (std::abs(u.z() * v.x()) + std::abs(u.x() * v.z())) +
                           std::abs(w.z()) * (std::abs(u.x() * v.y()) + std::abs(u.y() * v.x()));
  const double band = maxOf(eps * e1.lpNorm<1>() * e2.lpNorm<1>(), kOrientErrorFactor * permanent);
  return det > band ? 1 : (det < -band ? -1 : 0);
}

/// CHECK_MIN_MAX of Guigue & Devillers (2003): with both triangles in canonical form (p1 and
/// p2 alone on their side of the other plane), the intervals on the planes' common line
/// overlap iff both predicates are <= 0.
Verdict checkMinMax(const Vec3& p1, const Vec3& q1, const Vec3& r1, const Vec3& p2, const Vec3& q2,
                    const Vec3& r2, double eps) {
  const int s1 = decidedOrientation(q1, p2, p1, q2, q1 - p1, q2 - p2, eps);
  if (s1 > 0) return Verdict::Disjoint;
  const int s2 = decidedOrientation(p1, p2, r1, r2, r1 - p1, r2 - p2, eps);
  if (s2 > 0) return Verdict::Disjoint;
  return s1 < 0 && s2 < 0 ? Verdict::Intersect : Verdict::Unsure;
}

/// TRI_TRI_3D of Guigue & Devillers for strictly non-zero plane values: puts the second
/// triangle in canonical form.
Verdict canonicalSecond(const Vec3& p1, const Vec3& q1, const Vec3& r1, const Vec3& p2,
                        const Vec3& q2, const Vec3& r2, double dp2, double dq2, double dr2,
                        double eps) {
  if (dp2 > 0) {
    if (dq2 > 0) return checkMinMax(p1, r1, q1, r2, p2, q2, eps);
    if (dr2 > 0) return checkMinMax(p1, r1, q1, q2, r2, p2, eps);
    return checkMinMax(p1, q1, r1, p2, q2, r2, eps);
  }
  if (dq2 < 0) return checkMinMax(p1, q1, r1, r2, p2, q2, eps);
  if (dr2 < 0) return checkMinMax(p1, q1, r1, q2, r2, p2, eps);
  return checkMinMax(p1, r1, q1, p2, q2, r2, eps);
}

/// Guigue-Devillers for triangles whose six plane values are all strictly non-zero (and not
/// all on one side). dA: a's vertices against b's plane; dB: b's against a's plane.
Verdict guigueDevillers(const Vec3& p1, const Vec3& q1, const Vec3& r1, const Vec3& p2,
                        const Vec3& q2, const Vec3& r2, const double (&dA)[3],
                        const double (&dB)[3], double eps) {
  if (dA[0] > 0) {
    if (dA[1] > 0) return canonicalSecond(r1, p1, q1, p2, r2, q2, dB[0], dB[2], dB[1], eps);
    if (dA[2] > 0) return canonicalSecond(q1, r1, p1, p2, r2, q2, dB[0], dB[2], dB[1], eps);
    return canonicalSecond(p1, q1, r1, p2, q2, r2, dB[0], dB[1], dB[2], eps);
  }
  if (dA[1] < 0) return canonicalSecond(r1, p1, q1, p2, q2, r2, dB[0], dB[1], dB[2], eps);
  if (dA[2] < 0) return canonicalSecond(q1, r1, p1, p2, q2, r2, dB[0], dB[1], dB[2], eps);
  return canonicalSecond(p1, q1, r1, p2, r2, q2, dB[0], dB[2], dB[1], eps);
}

// ---- Complete rule --------------------------------------------------------------------------

/// One triangle as seen by the straddling stage.
struct Side {
  Vec3 v[3];        ///< vertices, a0 at the origin
  Vec3 n;           ///< normal as computed by the fast stage (not normalised)
  double band;      ///< zero band of plane values against this triangle's plane
  double other[3];  ///< plane values of the other triangle's vertices against this plane
};

/// A non-degenerate triangle projected onto the coordinate plane that drops the dominant axis
/// of its normal (the projection then shrinks in-plane distances by at most sqrt(3) and keeps
/// the triangle far from degenerate).
struct Target2D {
  int u = 0, w = 1;   ///< the two kept axes
  Vec2 t[3];          ///< counter-clockwise
  double edgeTol[3];  ///< eps * |t[i+1] - t[i]|_1, the zero band of edge function i
};

Target2D project(const Side& s, double eps) {
  Target2D p;
  const Vec3 an = s.n.cwiseAbs();
  const int drop = an.x() >= an.y() ? (an.x() >= an.z() ? 0 : 2) : (an.y() >= an.z() ? 1 : 2);
  // Cyclic order (drop+1, drop+2) makes the projected orientation the sign of n[drop].
  p.u = (drop + 1) % 3;
  p.w = (drop + 2) % 3;
  for (int i = 0; i < 3; ++i) p.t[i] = Vec2(s.v[i][p.u], s.v[i][p.w]);
  if (s.n[drop] < 0) std::swap(p.t[1], p.t[2]);
  for (int i = 0; i < 3; ++i) {
    // The 1-norm is >= the Euclidean length, so every point within eps of the edge line (in
    // the projection) is snapped; it avoids a square root per edge.
    p.edgeTol[i] = eps * (p.t[(i + 1) % 3] - p.t[i]).lpNorm<1>();
  }
  return p;
}

/// Closed segment pq against a non-degenerate triangle. dp, dq are the plane values of p and q
/// against the triangle's plane, band their zero band (> 0).
bool segmentMeetsTriangle(const Vec3& p, const Vec3& q, double dp, double dq, double band,
                          const Target2D& tri, double eps) {
  if ((dp > band && dq > band) || (dp < -band && dq < -band)) return false;
  // Keep only the part of the segment within 2 * band of the plane. A computed plane value is
  // within band of the exact one, so the exact crossing point (value 0) lies inside the kept
  // part with a margin of band, and the clip's own rounding cannot push it out. This replaces
  // the ill-conditioned "intersection point" of a segment nearly parallel to the plane.
  const double slab = 2 * band;
  Vec3 c0 = p, c1 = q;
  // |dp| > slab and dq within band on the other side or inside the band: |dp - dq| >= band > 0
  // and the parameter lies in [0, 1).
  if (std::abs(dp) > slab) c0 = p + (q - p) * ((dp - std::copysign(slab, dp)) / (dp - dq));
  if (std::abs(dq) > slab) c1 = q + (p - q) * ((dq - std::copysign(slab, dq)) / (dq - dp));
  const Vec2 s0(c0[tri.u], c0[tri.w]), s1(c1[tri.u], c1[tri.w]);

  // Separating axes of a segment and a triangle in 2D: the triangle's three edge normals and
  // the segment's normal. A value within its tolerance counts as touching.
  for (int i = 0; i < 3; ++i) {
    const Vec2& a = tri.t[i];
    const Vec2 e = tri.t[(i + 1) % 3] - a;
    if (cross2(e, s0 - a) < -tri.edgeTol[i] && cross2(e, s1 - a) < -tri.edgeTol[i]) return false;
  }
  const Vec2 dir = s1 - s0;
  const double tol = eps * dir.lpNorm<1>();  // a point segment gives values 0: never separates
  const double f0 = cross2(dir, tri.t[0] - s0), f1 = cross2(dir, tri.t[1] - s0),
               f2 = cross2(dir, tri.t[2] - s0);
  return !allOnOneSide(f0, f1, f2, tol);
}


/// Squared distance between closed segments p1q1 and p2q2.
double segmentSegmentDistanceSq(const Vec3& p1, const Vec3& q1, const Vec3& p2, const Vec3& q2) {
  Vec3 c1, c2;
  detail::closestSegmentPoints(p1, q1, p2, q2, c1, c2);
  return (c1 - c2).squaredNorm();
}

/// Index k of the longest edge (v[k], v[k+1]) and its squared length.
int longestEdge(const Side& s, double& lengthSq) {
  const double l0 = (s.v[1] - s.v[0]).squaredNorm(), l1 = (s.v[2] - s.v[1]).squaredNorm(),
               l2 = (s.v[0] - s.v[2]).squaredNorm();
  const int k = l0 >= l1 ? (l0 >= l2 ? 0 : 2) : (l1 >= l2 ? 1 : 2);
  lengthSq = maxOf(l0, maxOf(l1, l2));
  return k;
}

/// The planes do not separate the triangles: decide with the complete rule. Out of line: the
/// hot function is the plane rejection.
[[gnu::noinline]] bool decideStraddling(const Side& A, const Side& B, double eps) {
  // Degenerate: smallest height |n| / longest edge <= eps. Such a triangle lies within eps of
  // its longest edge, and its computed normal direction may be meaningless. Above the
  // threshold the normal's rounding error is below ~1e-3 of |n|, so its dominant axis is sound.
  double lenA = 0, lenB = 0;
  const int kA = longestEdge(A, lenA), kB = longestEdge(B, lenB);
  const bool degA = A.n.squaredNorm() <= eps * eps * lenA;
  const bool degB = B.n.squaredNorm() <= eps * eps * lenB;
  const int kA1 = (kA + 1) % 3, kB1 = (kB + 1) % 3;

  if (degA && degB) {
    return segmentSegmentDistanceSq(A.v[kA], A.v[kA1], B.v[kB], B.v[kB1]) <= eps * eps;
  }
  if (degA) {
    const Target2D tb = project(B, eps);
    return segmentMeetsTriangle(A.v[kA], A.v[kA1], B.other[kA], B.other[kA1], B.band, tb, eps);
  }
  if (degB) {
    const Target2D ta = project(A, eps);
    return segmentMeetsTriangle(B.v[kB], B.v[kB1], A.other[kB], A.other[kB1], A.band, ta, eps);
  }
  const Target2D ta = project(A, eps);
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3;
    if (segmentMeetsTriangle(B.v[k], B.v[k1], A.other[k], A.other[k1], A.band, ta, eps)) {
      return true;
    }
  }
  const Target2D tb = project(B, eps);
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3;
    if (segmentMeetsTriangle(A.v[k], A.v[k1], B.other[k], B.other[k1], B.band, tb, eps)) {
      return true;
    }
  }
  return false;
}

/// Largest extent along x, y or z of {0, p1, p2, q0, q1, q2}. Plain scalar code: Eigen's
/// chained cwiseMin/cwiseMax expressions are not inlined at -O2 and cost more than the test.
inline double axisExtent(double p1, double p2, double q0, double q1, double q2) {
  const double lo = minOf(minOf(minOf(0.0, p1), minOf(p2, q0)), minOf(q1, q2));
  const double hi = maxOf(maxOf(maxOf(0.0, p1), maxOf(p2, q0)), maxOf(q1, q2));
  return hi - lo;
}
inline double extent(const Vec3& p1, const Vec3& p2, const Vec3& q0, const Vec3& q1,
                     const Vec3& q2) {
  return maxOf(maxOf(axisExtent(p1.x(), p2.x(), q0.x(), q1.x(), q2.x()),
                     axisExtent(p1.y(), p2.y(), q0.y(), q1.y(), q2.y())),
               axisExtent(p1.z(), p2.z(), q0.z(), q1.z(), q2.z()));
}

/// The whole test on vertices translated so that a0 is the origin (p1 = a1 - a0, ...), with
/// scale L in the unscaled range.
bool intersectTranslated(const Vec3& p1, const Vec3& p2, const Vec3& q0, const Vec3& q1,
                         const Vec3& q2, double scale) {
  const double eps = kTriangleTestRelativeTolerance * scale;

  // b against a's plane. a0 is the origin, so the plane values are plain dot products.
  const Vec3 nA = p1.cross(p2);
  const double bandA = planeBand(nA, eps, scale, crossAbsSum(p1, p2));
  const double dB0 = nA.dot(q0), dB1 = nA.dot(q1), dB2 = nA.dot(q2);
  if (allOnOneSide(dB0, dB1, dB2, bandA)) return false;

  // a against b's plane (rounding of the differences is inside kPlaneErrorFactor).
  const Vec3 f1 = q1 - q0, f2 = q2 - q0;
  const Vec3 nB = f1.cross(f2);
  const double bandB = planeBand(nB, eps, scale, crossAbsSum(f1, f2));
  const double dA0 = -nB.dot(q0), dA1 = nB.dot(p1 - q0), dA2 = nB.dot(p2 - q0);
  if (allOnOneSide(dA0, dA1, dA2, bandB)) return false;

  // A NaN coordinate makes some plane value NaN (and NaN never rejects), so this one check,
  // off the fast path, refuses NaN input. Finite values cannot overflow here (degree 3).
  if (!std::isfinite(dA0 + dA1 + dA2 + dB0 + dB1 + dB2)) return false;
  const Side A{{Vec3::Zero(), p1, p2}, nA, bandA, {dB0, dB1, dB2}};
  const Side B{{q0, q1, q2}, nB, bandB, {dA0, dA1, dA2}};
  const bool allStrict = minOf(std::abs(dA0), minOf(std::abs(dA1), std::abs(dA2))) > bandB &&
                         minOf(std::abs(dB0), minOf(std::abs(dB1), std::abs(dB2))) > bandA;
  if (allStrict) {
    const Verdict v =
        guigueDevillers(A.v[0], A.v[1], A.v[2], B.v[0], B.v[1], B.v[2], B.other, A.other, eps);
    if (v != Verdict::Unsure) return v == Verdict::Intersect;
  }
  return decideStraddling(A, B, eps);
}

/// Rare path: scale outside [kMinUnscaledExtent, kMaxUnscaledExtent], zero, or non-finite.
/// Rescales and calls trianglesIntersect again, which then takes the normal path (the new
/// scale is exactly in [1, 2), so it recurses at most once). Kept out of line so that the hot
/// function stays small.
[[gnu::noinline, gnu::cold]] bool intersectRescaled(const Vec3& a0, const Vec3& a1, const Vec3& a2,
                                                    const Vec3& b0, const Vec3& b1,
                                                    const Vec3& b2) {
  if (!(a0.allFinite() && a1.allFinite() && a2.allFinite() && b0.allFinite() && b1.allFinite() &&
        b2.allFinite())) {
    return false;
  }
  // Differences of finite coordinates near DBL_MAX can overflow; a power-of-two pre-scale is
  // exact (bar coordinates far below the tolerance) and makes that impossible.
  const bool huge = !std::isfinite(extent(a1 - a0, a2 - a0, b0 - a0, b1 - a0, b2 - a0));
  const double pre = huge ? 0x1p-2 : 1.0;
  const Vec3 o = pre * a0;
  Vec3 v[5] = {pre * a1 - o, pre * a2 - o, pre * b0 - o, pre * b1 - o, pre * b2 - o};
  const double scale = extent(v[0], v[1], v[2], v[3], v[4]);
  if (scale == 0) return true;  // all six vertices coincide
  // Bring L to [1, 2). ldexp is exact and, unlike multiplying by 2^-e, also works when L is
  // subnormal (2^-e would overflow). Translating by a0 = 0 again is exact, so the second call
  // sees exactly these coordinates.
  const int e = std::ilogb(scale);
  for (Vec3& x : v) x = x.unaryExpr([e](double c) { return std::ldexp(c, -e); });
  return trianglesIntersect(Vec3::Zero(), v[0], v[1], v[2], v[3], v[4]);
}

}  // namespace

bool trianglesIntersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                        const Vec3& b1, const Vec3& b2) {
  const Vec3 p1 = a1 - a0, p2 = a2 - a0, q0 = b0 - a0, q1 = b1 - a0, q2 = b2 - a0;
  const double scale = extent(p1, p2, q0, q1, q2);
  // Negated form so that NaN takes the rare path too.
  if (!(scale >= kMinUnscaledExtent && scale <= kMaxUnscaledExtent)) {
    return intersectRescaled(a0, a1, a2, b0, b1, b2);
  }
  return intersectTranslated(p1, p2, q0, q1, q2, scale);
}

}  // namespace adb
