// Tests of trianglesIntersect: known answers (separated, intersecting, touching, coplanar,
// degenerate, tolerance), symmetry and invariances, and random pairs against independent
// oracles (Moller's interval test in long double; exact integer separating axes; exact integer
// predicates for degenerate triangles).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "adb/core/triangle_test.h"

namespace adb {
namespace {

struct Tri {
  Vec3 v[3];
};

Tri tri(const Vec3& a, const Vec3& b, const Vec3& c) { return Tri{{a, b, c}}; }

bool hit(const Tri& a, const Tri& b) {
  return trianglesIntersect(a.v[0], a.v[1], a.v[2], b.v[0], b.v[1], b.v[2]);
}

constexpr int kPerm[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};

Tri permuted(const Tri& t, int k) {
  return tri(t.v[kPerm[k][0]], t.v[kPerm[k][1]], t.v[kPerm[k][2]]);
}

/// Number of the 72 argument orders (6 x 6 vertex orders, both triangle orders) that report
/// an intersection: 0 or 72 when the test is symmetric.
int countHits(const Tri& a, const Tri& b) {
  int n = 0;
  for (int i = 0; i < 6; ++i) {
    const Tri pa = permuted(a, i);
    for (int j = 0; j < 6; ++j) {
      const Tri pb = permuted(b, j);
      n += hit(pa, pb) ? 1 : 0;
      n += hit(pb, pa) ? 1 : 0;
    }
  }
  return n;
}

Tri mapped(const Tri& t, const std::function<Vec3(const Vec3&)>& f) {
  return tri(f(t.v[0]), f(t.v[1]), f(t.v[2]));
}

struct Transform {
  std::string name;
  std::function<Vec3(const Vec3&)> f;
};

Transform scaling(const std::string& name, double s) {
  return {name, [s](const Vec3& x) -> Vec3 { return s * x; }};
}

Mat3 rotation(double angle, const Vec3& axis) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

/// Transforms under which small-integer / dyadic configurations stay bit-exact: powers of two
/// (in the unscaled range, and far outside it, including subnormal coordinates), an integer
/// translation, and integer affine maps (intersection is affine invariant).
std::vector<Transform> exactTransforms() {
  Mat3 m1, m2;
  m1 << 1, 1, 0, 0, 1, 1, 1, 0, 1;    // det 2
  m2 << 2, -1, 0, 1, 1, -1, 0, 1, 2;  // det 8
  return {
      scaling("identity", 1.0),
      scaling("x2^-30", std::ldexp(1.0, -30)),
      scaling("x2^30", std::ldexp(1.0, 30)),
      scaling("x2^-700", std::ldexp(1.0, -700)),
      scaling("x2^700", std::ldexp(1.0, 700)),
      scaling("x2^-1040 (subnormal)", std::ldexp(1.0, -1040)),
      {"translate 1e5", [](const Vec3& x) -> Vec3 { return x + Vec3(1e5, -2e5, 3e5); }},
      {"integer affine 1", [m1](const Vec3& x) -> Vec3 { return m1 * x + Vec3(3, -1, 2); }},
      {"integer affine 2", [m2](const Vec3& x) -> Vec3 { return m2 * x; }},
  };
}

/// Transforms that round coordinates by a few ulps: far below the tolerance, so the answer
/// of every known case (touching ones included) must not change.
std::vector<Transform> roundingTransforms() {
  const Mat3 r1 = rotation(0.7, Vec3(1, 2, 3)), r2 = rotation(2.1, Vec3(-3, 1, 0.5));
  return {
      scaling("x1e-3", 1e-3),
      scaling("x1e3", 1e3),
      {"rotation 1", [r1](const Vec3& x) -> Vec3 { return r1 * x; }},
      {"rotation 2 x1e3 + shift",
       [r2](const Vec3& x) -> Vec3 { return 1e3 * (r2 * x) + Vec3(0.125, -7.5, 2.25); }},
  };
}

/// Known-answer check: every argument order, under every exact transform and every rounding
/// transform, gives `expected`.
void checkHit(const Tri& a, const Tri& b, bool expected) {
  std::vector<Transform> ts = exactTransforms();
  for (Transform& t : roundingTransforms()) ts.push_back(std::move(t));
  for (const Transform& t : ts) {
    EXPECT_EQ(countHits(mapped(a, t.f), mapped(b, t.f)), expected ? 72 : 0)
        << "transform: " << t.name;
  }
}

/// Only argument orders and powers of two: for cases whose gap is near the tolerance.
void checkHitExactOnly(const Tri& a, const Tri& b, bool expected) {
  for (double s : {1.0, std::ldexp(1.0, -40), std::ldexp(1.0, 40), std::ldexp(1.0, 600)}) {
    const Tri sa = mapped(a, [s](const Vec3& x) -> Vec3 { return s * x; });
    const Tri sb = mapped(b, [s](const Vec3& x) -> Vec3 { return s * x; });
    EXPECT_EQ(countHits(sa, sb), expected ? 72 : 0) << "scale " << s;
  }
}

// Known-answer macros: failures name the line of the case.
#define EXPECT_HIT(...)         \
  do {                          \
    SCOPED_TRACE("known case"); \
    checkHit(__VA_ARGS__);      \
  } while (0)
#define EXPECT_HIT_EXACT_ONLY(...)  \
  do {                              \
    SCOPED_TRACE("known case");     \
    checkHitExactOnly(__VA_ARGS__); \
  } while (0)

Tri lifted(const Tri& t, const Vec3& d) { return tri(t.v[0] + d, t.v[1] + d, t.v[2] + d); }

// The reference triangle of the known-answer tests: z = 0, legs 4 along x and y.
const Tri kT0 = tri(Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(0, 4, 0));
const double kGap = std::ldexp(1.0, -10);  // a clear gap: ~1e9 times the tolerance

// ---- Separated and intersecting, clear margins ---------------------------------------------

TEST(TriangleTest, SeparatedParallelPlanes) {
  EXPECT_HIT(kT0, lifted(kT0, Vec3(0, 0, 1)), false);
  EXPECT_HIT(kT0, lifted(kT0, Vec3(0, 0, -kGap)), false);
}

TEST(TriangleTest, SeparatedButPlanesStraddle) {
  // b stands in the plane y = 1 and crosses z = 0 at x in [5.33, 6.67], beyond a's hypotenuse.
  EXPECT_HIT(kT0, tri(Vec3(5, 1, -1), Vec3(7, 1, -1), Vec3(6, 1, 2)), false);
  // Two "X" triangles whose edges pass each other with a gap of 1/4.
  EXPECT_HIT(tri(Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(2, 0, 3)),
             tri(Vec3(2, 0.25, 1), Vec3(2, 3, -1), Vec3(2, 3, 2)), false);
}

TEST(TriangleTest, IntersectingPiercing) {
  EXPECT_HIT(kT0, tri(Vec3(1, 1, -1), Vec3(2, 1, 1), Vec3(1, 2, 1)), true);
  // A large b cut by a small a: a's interior is crossed, no vertex of either is inside.
  EXPECT_HIT(tri(Vec3(-8, -8, 0), Vec3(8, -8, 0), Vec3(0, 8, 0)),
             tri(Vec3(0, -1, -1), Vec3(1, 1, 1), Vec3(-1, 1, 1)), true);
}

TEST(TriangleTest, IntersectingEdgeThroughFace) {
  // b (plane y = 1) meets z = 0 in x in [-0.5, 1.75]; a's leg x = 0 passes through b.
  EXPECT_HIT(kT0, tri(Vec3(-1, 1, -1), Vec3(2, 1, -1), Vec3(1, 1, 3)), true);
  // Interlocked: each triangle has exactly one edge through the other.
  EXPECT_HIT(tri(Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(2, 0, 4)),
             tri(Vec3(2, -2, 1), Vec3(2, 2, 1), Vec3(2, 0, -3)), true);
}

// ---- Touching ---------------------------------------------------------------------------------

TEST(TriangleTest, TouchingVertexOnFace) {
  const Tri b = tri(Vec3(1, 1, 0), Vec3(2, 1, 2), Vec3(1, 2, 2));
  EXPECT_HIT(kT0, b, true);
  EXPECT_HIT(kT0, lifted(b, Vec3(0, 0, kGap)), false);
}

TEST(TriangleTest, TouchingVertexOnEdge) {
  const Tri b = tri(Vec3(2, 0, 0), Vec3(2, -1, 1), Vec3(3, -1, -1));
  EXPECT_HIT(kT0, b, true);
  EXPECT_HIT(kT0, lifted(b, Vec3(0, -kGap, 0)), false);
}

TEST(TriangleTest, TouchingEdgeOnEdgeCrossing) {
  // b in the plane x = 2, y <= 0: its edge x = 2, y = 0 crosses a's edge y = 0 at (2, 0, 0).
  const Tri b = tri(Vec3(2, 0, -1), Vec3(2, 0, 1), Vec3(2, -3, 0));
  EXPECT_HIT(kT0, b, true);
  EXPECT_HIT(kT0, lifted(b, Vec3(0, -kGap, 0)), false);
}

TEST(TriangleTest, TouchingVertexOnVertex) {
  const Tri b = tri(Vec3(4, 0, 0), Vec3(5, 1, 1), Vec3(5, -1, 1));
  EXPECT_HIT(kT0, b, true);
  EXPECT_HIT(kT0, lifted(b, Vec3(kGap, 0, 0)), false);
}

TEST(TriangleTest, TouchingSharedEdge) {
  EXPECT_HIT(kT0, tri(Vec3(4, 0, 0), Vec3(0, 4, 0), Vec3(4, 4, 3)), true);    // folded
  EXPECT_HIT(kT0, tri(Vec3(4, 0, 0), Vec3(0, 4, 0), Vec3(4, 4, 0)), true);    // flat neighbour
  EXPECT_HIT(kT0, tri(Vec3(0, 0, 0), Vec3(-4, 0, 1), Vec3(0, -4, 1)), true);  // shared vertex
}

TEST(TriangleTest, TouchingEdgeLyingOnFace) {
  const Tri b = tri(Vec3(1, 1, 0), Vec3(2, 1, 0), Vec3(1, 1, 2));
  EXPECT_HIT(kT0, b, true);
  EXPECT_HIT(kT0, lifted(b, Vec3(0, 0, kGap)), false);
}

// ---- Coplanar ---------------------------------------------------------------------------------

TEST(TriangleTest, CoplanarOverlap) {
  EXPECT_HIT(kT0, tri(Vec3(1, 1, 0), Vec3(5, 1, 0), Vec3(1, 5, 0)), true);
  EXPECT_HIT(kT0, kT0, true);  // identical
  // Star of David: edges cross, no vertex inside the other.
  EXPECT_HIT(tri(Vec3(0, 0, 0), Vec3(6, 0, 0), Vec3(3, 6, 0)),
             tri(Vec3(0, 4, 0), Vec3(6, 4, 0), Vec3(3, -2, 0)), true);
}

TEST(TriangleTest, CoplanarDisjoint) {
  EXPECT_HIT(kT0, tri(Vec3(3, 3, 0), Vec3(6, 3, 0), Vec3(3, 6, 0)), false);
  EXPECT_HIT(kT0, tri(Vec3(2 + kGap, 2, 0), Vec3(5, 3, 0), Vec3(3, 5, 0)), false);
}

TEST(TriangleTest, CoplanarContainment) {
  EXPECT_HIT(kT0, tri(Vec3(1, 1, 0), Vec3(2, 1, 0), Vec3(1, 2, 0)), true);
  // Contained and touching the boundary from inside.
  EXPECT_HIT(kT0, tri(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0)), true);
}

TEST(TriangleTest, CoplanarTouching) {
  EXPECT_HIT(kT0, tri(Vec3(4, 0, 0), Vec3(6, -1, 0), Vec3(6, 1, 0)), true);  // vertex-vertex
  EXPECT_HIT(kT0, tri(Vec3(2, 2, 0), Vec3(4, 3, 0), Vec3(3, 4, 0)), true);   // vertex on edge
  EXPECT_HIT(kT0, tri(Vec3(2, 0, 0), Vec3(6, 0, 0), Vec3(4, -2, 0)), true);  // collinear edges
  EXPECT_HIT(kT0, tri(Vec3(4 + kGap, 0, 0), Vec3(6, -1, 0), Vec3(6, 1, 0)), false);
}

// ---- Degenerate -------------------------------------------------------------------------------

Tri point(const Vec3& p) { return tri(p, p, p); }

TEST(TriangleTest, DegeneratePointAgainstTriangle) {
  EXPECT_HIT(kT0, point(Vec3(1, 1, 0)), true);  // on the face
  EXPECT_HIT(kT0, point(Vec3(2, 0, 0)), true);  // on an edge
  EXPECT_HIT(kT0, point(Vec3(4, 0, 0)), true);  // on a vertex
  EXPECT_HIT(kT0, point(Vec3(1, 1, kGap)), false);
  EXPECT_HIT(kT0, point(Vec3(3, 3, 0)), false);  // in the plane, outside
  EXPECT_HIT(kT0, point(Vec3(2 + kGap, 2, 0)), false);
}

TEST(TriangleTest, DegeneratePointAgainstPoint) {
  EXPECT_HIT(point(Vec3(1, 2, 3)), point(Vec3(1, 2, 3)), true);
  EXPECT_HIT(point(Vec3(1, 2, 3)), point(Vec3(1, 2, 3 + kGap)), false);
  EXPECT_HIT(point(Vec3(0, 0, 0)), point(Vec3(0, 0, 0)), true);  // all six vertices coincide
}

TEST(TriangleTest, DegenerateSegmentAgainstTriangle) {
  // Collinear (middle vertex) and repeated-vertex forms of the same segment.
  EXPECT_HIT(kT0, tri(Vec3(1, 1, -1), Vec3(1, 1, 1), Vec3(1, 1, 0)), true);
  EXPECT_HIT(kT0, tri(Vec3(1, 1, -1), Vec3(1, 1, 1), Vec3(1, 1, 1)), true);
  EXPECT_HIT(kT0, tri(Vec3(5, 5, -1), Vec3(5, 5, 1), Vec3(5, 5, 0)), false);
  // Ending on the face, and the same lifted off it.
  EXPECT_HIT(kT0, tri(Vec3(1, 1, 0), Vec3(1, 1, 2), Vec3(1, 1, 1)), true);
  EXPECT_HIT(kT0, tri(Vec3(1, 1, kGap), Vec3(1, 1, 2), Vec3(1, 1, 1)), false);
  // Lying in the plane: crossing, outside, touching the hypotenuse with its end.
  EXPECT_HIT(kT0, tri(Vec3(-1, 1, 0), Vec3(5, 1, 0), Vec3(2, 1, 0)), true);
  EXPECT_HIT(kT0, tri(Vec3(3, 3, 0), Vec3(6, 0, 0), Vec3(6, 0, 0)), false);
  EXPECT_HIT(kT0, tri(Vec3(2, 2, 0), Vec3(5, 5, 0), Vec3(3, 3, 0)), true);
  // Crossing an edge of the triangle from outside its plane.
  EXPECT_HIT(kT0, tri(Vec3(2, -1, 1), Vec3(2, 1, -1), Vec3(2, 0, 0)), true);
  EXPECT_HIT(kT0, tri(Vec3(2, -1, 1), Vec3(2, 1, -1 - kGap), Vec3(2, 1, -1 - kGap)), false);
}

TEST(TriangleTest, DegenerateSegmentAgainstSegment) {
  const Tri s = tri(Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(2, 0, 0));
  EXPECT_HIT(s, tri(Vec3(2, -1, 0), Vec3(2, 1, 0), Vec3(2, 1, 0)), true);   // crossing
  EXPECT_HIT(s, tri(Vec3(2, -1, 1), Vec3(2, 1, 1), Vec3(2, 0, 1)), false);  // skew, apart
  EXPECT_HIT(s, tri(Vec3(3, 0, 0), Vec3(6, 0, 0), Vec3(5, 0, 0)), true);    // collinear overlap
  EXPECT_HIT(s, tri(Vec3(4, 0, 0), Vec3(6, 0, 0), Vec3(6, 0, 0)), true);    // end to end
  EXPECT_HIT(s, tri(Vec3(4 + kGap, 0, 0), Vec3(6, 0, 0), Vec3(5, 0, 0)), false);
  EXPECT_HIT(s, tri(Vec3(1, 1, 0), Vec3(3, 1, 0), Vec3(3, 1, 0)), false);  // parallel
  EXPECT_HIT(s, tri(Vec3(2, 0, 0), Vec3(2, 3, 0), Vec3(2, 3, 0)), true);   // T
  EXPECT_HIT(s, point(Vec3(1, 0, 0)), true);
  EXPECT_HIT(s, point(Vec3(1, kGap, 0)), false);
  EXPECT_HIT(s, point(Vec3(-kGap, 0, 0)), false);
}

TEST(TriangleTest, DegenerateSliverBelowToleranceIsItsLongestEdge) {
  // Height 2^-50 (relative 3e-16 < tolerance): a segment along y = 0.
  const Tri sliver = tri(Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(2, std::ldexp(1.0, -50), 0));
  EXPECT_HIT_EXACT_ONLY(sliver, tri(Vec3(1, 0, -1), Vec3(1, 0, 1), Vec3(1, -1, 0)), true);
  EXPECT_HIT_EXACT_ONLY(sliver, tri(Vec3(1, kGap, -1), Vec3(1, kGap, 1), Vec3(1, 1, 0)), false);
}

TEST(TriangleTest, ThinTriangleAboveToleranceIsATriangle) {
  // Height 2^-20 (relative 2e-7): still a real triangle.
  const double h = std::ldexp(1.0, -20);
  const Tri thin = tri(Vec3(0, 0, 0), Vec3(4, 0, 0), Vec3(2, h, 0));
  // A vertical segment through its interior, and just beyond its apex.
  EXPECT_HIT(thin, tri(Vec3(2, h / 4, -1), Vec3(2, h / 4, 1), Vec3(2, h / 4, 1)), true);
  EXPECT_HIT(thin, tri(Vec3(2, 2 * h, -1), Vec3(2, 2 * h, 1), Vec3(2, 2 * h, 1)), false);
  // Coplanar sliver pair, parallel and apart by h.
  EXPECT_HIT(thin, lifted(thin, Vec3(0, 2 * h, 0)), false);
}

// ---- Tolerance --------------------------------------------------------------------------------

TEST(TriangleTest, ToleranceSnapsGapsBelowEps) {
  // L = 4 here, so eps = 4e-12.
  EXPECT_HIT_EXACT_ONLY(kT0, tri(Vec3(1, 1, 1e-12), Vec3(2, 1, 2), Vec3(1, 2, 2)), true);
  EXPECT_HIT_EXACT_ONLY(kT0, tri(Vec3(1, 1, -1e-12), Vec3(2, 1, -2), Vec3(1, 2, -2)), true);
  // In the plane, 1e-12 beyond the hypotenuse.
  EXPECT_HIT_EXACT_ONLY(kT0, tri(Vec3(2 + 5e-13, 2 + 5e-13, 0), Vec3(4, 3, 0), Vec3(3, 4, 0)),
                        true);
  EXPECT_HIT_EXACT_ONLY(kT0, point(Vec3(2 + 5e-13, 2 + 5e-13, 0)), true);
}

TEST(TriangleTest, ToleranceDoesNotSnapLargerGaps) {
  EXPECT_HIT_EXACT_ONLY(kT0, tri(Vec3(1, 1, 1e-10), Vec3(2, 1, 2), Vec3(1, 2, 2)), false);
  EXPECT_HIT_EXACT_ONLY(kT0, tri(Vec3(2 + 1e-10, 2 + 1e-10, 0), Vec3(4, 3, 0), Vec3(3, 4, 0)),
                        false);
  EXPECT_HIT_EXACT_ONLY(kT0, point(Vec3(2 + 1e-10, 2 + 1e-10, 0)), false);
}

// ---- Robustness of the input handling -------------------------------------------------------

TEST(TriangleTest, NonFiniteInputGivesFalse) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double bad : {nan, inf, -inf}) {
    for (int k = 0; k < 6; ++k) {
      Tri a = kT0, b = tri(Vec3(1, 1, -1), Vec3(2, 1, 1), Vec3(1, 2, 1));
      (k < 3 ? a.v[k] : b.v[k - 3]).y() = bad;
      EXPECT_FALSE(hit(a, b)) << "value " << bad << " at vertex " << k;
      EXPECT_FALSE(hit(b, a)) << "value " << bad << " at vertex " << k;
    }
  }
}

TEST(TriangleTest, ScaleHugeCoordinatesWhoseDifferencesOverflow) {
  // Coordinates up to 2^1023; differences reach 2^1024 = overflow without the pre-scale.
  const double s = std::ldexp(1.0, 1021);
  const Tri a = tri(Vec3(-4, -4, 0), Vec3(4, -4, 0), Vec3(0, 4, 0));
  const Tri touching = tri(Vec3(0, 0, 0), Vec3(1, 1, 4), Vec3(-1, 1, 4));
  const Tri apart = lifted(touching, Vec3(0, 0, 0.5));
  auto sc = [s](const Tri& t) { return mapped(t, [s](const Vec3& x) -> Vec3 { return s * x; }); };
  EXPECT_EQ(countHits(sc(a), sc(touching)), 72);
  EXPECT_EQ(countHits(sc(a), sc(apart)), 0);
  EXPECT_EQ(countHits(sc(a), sc(a)), 72);
}

// ---- Independent oracles ----------------------------------------------------------------------

using LVec = Eigen::Matrix<long double, 3, 1>;

enum class Verdict { Disjoint, Intersect, Unclear };

/// Moller's interval-overlap test in long double, for general-position non-degenerate pairs.
/// Unclear when a margin (plane distance or interval gap/overlap) is below 1e-6 of the scale,
/// when a triangle is a sliver or when the planes are nearly parallel.
Verdict mollerOracle(const Tri& ta, const Tri& tb) {
  LVec a[3], b[3];
  LVec lo = LVec::Constant(std::numeric_limits<long double>::infinity()), hi = -lo;
  for (int i = 0; i < 3; ++i) {
    a[i] = ta.v[i].cast<long double>();
    b[i] = tb.v[i].cast<long double>();
    lo = lo.cwiseMin(a[i]).cwiseMin(b[i]);
    hi = hi.cwiseMax(a[i]).cwiseMax(b[i]);
  }
  const long double scale = (hi - lo).maxCoeff();
  const long double margin = 1e-6L * scale;
  auto normal = [](const LVec(&t)[3], LVec& n) {
    n = (t[1] - t[0]).cross(t[2] - t[0]);
    const long double longest = std::max(
        {(t[1] - t[0]).squaredNorm(), (t[2] - t[1]).squaredNorm(), (t[0] - t[2]).squaredNorm()});
    if (n.norm() < 1e-4L * longest) return false;
    n.normalize();
    return true;
  };
  LVec n1, n2;
  if (!normal(a, n1) || !normal(b, n2)) return Verdict::Unclear;
  long double da[3], db[3];
  for (int i = 0; i < 3; ++i) {
    da[i] = n2.dot(a[i] - b[0]);
    db[i] = n1.dot(b[i] - a[0]);
    if (std::abs(da[i]) < margin || std::abs(db[i]) < margin) return Verdict::Unclear;
  }
  auto sameSide = [](const long double(&d)[3]) {
    return (d[0] > 0) == (d[1] > 0) && (d[1] > 0) == (d[2] > 0);
  };
  if (sameSide(da) || sameSide(db)) return Verdict::Disjoint;
  LVec dir = n1.cross(n2);
  if (dir.norm() < 1e-3L) return Verdict::Unclear;
  dir.normalize();
  // The interval of a triangle on the planes' common line: its two edges from the vertex
  // alone on its side cross the other plane there.
  auto interval = [&dir](const LVec(&t)[3], const long double(&d)[3], long double& mn,
                         long double& mx) {
    int k = 0;
    if ((d[0] > 0) == (d[1] > 0))
      k = 2;
    else if ((d[0] > 0) == (d[2] > 0))
      k = 1;
    const long double pk = dir.dot(t[k]);
    long double x[2];
    int m = 0;
    for (int j = 0; j < 3; ++j) {
      if (j == k) continue;
      x[m++] = pk + (dir.dot(t[j]) - pk) * d[k] / (d[k] - d[j]);
    }
    mn = std::min(x[0], x[1]);
    mx = std::max(x[0], x[1]);
  };
  long double lo1, hi1, lo2, hi2;
  interval(a, da, lo1, hi1);
  interval(b, db, lo2, hi2);
  const long double gap = std::max(lo1, lo2) - std::min(hi1, hi2);
  if (std::abs(gap) < margin) return Verdict::Unclear;
  return gap < 0 ? Verdict::Intersect : Verdict::Disjoint;
}

Vec3 uniformIn(std::mt19937& rng, double lo, double hi) {
  std::uniform_real_distribution<double> u(lo, hi);
  const double x = u(rng), y = u(rng), z = u(rng);
  return Vec3(x, y, z);
}

/// A random pair: big overlapping triangles, close small-against-big pairs, or needles; then
/// a random scale (1e-3 .. 1e3) and a translation of up to 100 times the size.
std::pair<Tri, Tri> randomPair(std::mt19937& rng) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const int mode = static_cast<int>(rng() % 3);
  Tri a = tri(uniformIn(rng, -1, 1), uniformIn(rng, -1, 1), uniformIn(rng, -1, 1));
  Tri b;
  if (mode == 0) {
    b = tri(uniformIn(rng, -1, 1), uniformIn(rng, -1, 1), uniformIn(rng, -1, 1));
  } else if (mode == 1) {
    // Small b around a random point of a (slightly off its plane).
    const double r = 0.02 + 0.5 * u01(rng);
    double w0 = u01(rng), w1 = u01(rng);
    if (w0 + w1 > 1) {
      w0 = 1 - w0;
      w1 = 1 - w1;
    }
    const Vec3 c = a.v[0] + w0 * (a.v[1] - a.v[0]) + w1 * (a.v[2] - a.v[0]) +
                   uniformIn(rng, -0.3 * r, 0.3 * r);
    b = tri(c + uniformIn(rng, -r, r), c + uniformIn(rng, -r, r), c + uniformIn(rng, -r, r));
  } else {
    // Needles (aspect down to ~1e-3) crossing each other.
    auto needle = [&]() {
      const Vec3 p = uniformIn(rng, -1, 1), q = uniformIn(rng, -1, 1);
      const double w = std::pow(10.0, -1 - 2 * u01(rng));
      return tri(p, q, 0.5 * (p + q) + w * uniformIn(rng, -1, 1));
    };
    a = needle();
    b = needle();
  }
  const double s = std::pow(10.0, -3 + 6 * u01(rng));
  const Vec3 t = s * uniformIn(rng, -100, 100);
  auto place = [&](const Tri& x) {
    return mapped(x, [&](const Vec3& v) -> Vec3 { return s * v + t; });
  };
  return {place(a), place(b)};
}

TEST(TriangleTest, RandomAgainstOracle) {
  std::mt19937 rng(12345);
  int checked = 0, intersecting = 0, disagreements = 0;
  for (int i = 0; i < 200000; ++i) {
    const auto [a, b] = randomPair(rng);
    const Verdict v = mollerOracle(a, b);
    if (v == Verdict::Unclear) continue;
    ++checked;
    const bool expected = v == Verdict::Intersect;
    intersecting += expected ? 1 : 0;
    if (hit(a, b) != expected || hit(b, a) != expected) {
      if (++disagreements <= 5) ADD_FAILURE() << "disagreement at pair " << i;
    }
  }
  EXPECT_EQ(disagreements, 0);
  EXPECT_GT(checked, 180000);
  EXPECT_GT(intersecting, 30000);
  EXPECT_GT(checked - intersecting, 30000);
}

// Exact integer oracle: separating axes with int64 arithmetic on small integer coordinates.
using I3 = std::array<std::int64_t, 3>;
struct ITri {
  I3 v[3];
};

I3 sub(const I3& a, const I3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
I3 cross(const I3& a, const I3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
std::int64_t dot(const I3& a, const I3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
bool isZero(const I3& a) { return a[0] == 0 && a[1] == 0 && a[2] == 0; }
I3 normalOf(const ITri& t) { return cross(sub(t.v[1], t.v[0]), sub(t.v[2], t.v[0])); }

Vec3 toVec(const I3& a) {
  return Vec3(static_cast<double>(a[0]), static_cast<double>(a[1]), static_cast<double>(a[2]));
}
Tri toTri(const ITri& t) { return tri(toVec(t.v[0]), toVec(t.v[1]), toVec(t.v[2])); }

/// Exact test for non-degenerate integer triangles. The axes are the facet normals of the
/// Minkowski difference: both normals and the nine edge cross products, plus the in-plane edge
/// normals when the planes are parallel. `touching` is set when the triangles meet but some
/// axis has projections that only touch (no interior overlap).
bool satOracle(const ITri& a, const ITri& b, bool& touching) {
  const I3 na = normalOf(a), nb = normalOf(b);
  std::vector<I3> axes = {na, nb};
  for (int i = 0; i < 3; ++i) {
    const I3 e = sub(a.v[(i + 1) % 3], a.v[i]);
    for (int j = 0; j < 3; ++j) axes.push_back(cross(e, sub(b.v[(j + 1) % 3], b.v[j])));
  }
  if (isZero(cross(na, nb))) {
    for (int i = 0; i < 3; ++i) {
      axes.push_back(cross(na, sub(a.v[(i + 1) % 3], a.v[i])));
      axes.push_back(cross(na, sub(b.v[(i + 1) % 3], b.v[i])));
    }
  }
  touching = false;
  for (const I3& m : axes) {
    if (isZero(m)) continue;
    std::int64_t loA = dot(m, a.v[0]), hiA = loA, loB = dot(m, b.v[0]), hiB = loB;
    for (int i = 1; i < 3; ++i) {
      loA = std::min(loA, dot(m, a.v[i]));
      hiA = std::max(hiA, dot(m, a.v[i]));
      loB = std::min(loB, dot(m, b.v[i]));
      hiB = std::max(hiB, dot(m, b.v[i]));
    }
    if (hiA < loB || hiB < loA) return false;
    if (hiA == loB || hiB == loA) touching = true;
  }
  return true;
}

I3 randomGridPoint(std::mt19937& rng, int n) {
  auto c = [&]() { return static_cast<std::int64_t>(rng() % static_cast<unsigned>(n)); };
  const std::int64_t x = c(), y = c(), z = c();
  return {x, y, z};
}

/// A random integer triangle: on a small 3D grid, or in a shared plane (z = 0 or an integer
/// embedding u U + v V + O) so that coplanar and touching configurations are frequent.
ITri randomIntegerTriangle(std::mt19937& rng, int mode, bool allowDegenerate) {
  const I3 U{1, 0, 1}, V{-1, 2, 1}, O{1, -2, 3};
  for (;;) {
    ITri t;
    for (I3& p : t.v) {
      if (mode == 0) {
        p = randomGridPoint(rng, 4);
      } else {
        const I3 g = randomGridPoint(rng, 5);
        if (mode == 1) {
          p = {g[0], g[1], 0};
        } else {
          for (int k = 0; k < 3; ++k) p[k] = g[0] * U[k] + g[1] * V[k] + O[k];
        }
      }
    }
    if (allowDegenerate || !isZero(normalOf(t))) return t;
  }
}

TEST(TriangleTest, RandomIntegerAgainstExactSeparatingAxes) {
  std::mt19937 rng(12345);
  int touchingCount = 0, coplanarCount = 0, intersecting = 0, disagreements = 0,
      rotatedDisagreements = 0;
  const Transform rotated = roundingTransforms()[3];
  const int kPairs = 100000;
  for (int i = 0; i < kPairs; ++i) {
    const int mode = static_cast<int>(rng() % 3);
    const ITri a = randomIntegerTriangle(rng, mode, false);
    const ITri b = randomIntegerTriangle(rng, mode, false);
    bool touching = false;
    const bool expected = satOracle(a, b, touching);
    intersecting += expected ? 1 : 0;
    touchingCount += (expected && touching) ? 1 : 0;
    coplanarCount += mode != 0 ? 1 : 0;
    const Tri fa = toTri(a), fb = toTri(b);
    if (hit(fa, fb) != expected || hit(fb, fa) != expected) {
      if (++disagreements <= 5) ADD_FAILURE() << "disagreement at pair " << i;
    }
    // Rotated, scaled and shifted, the coordinates round by ~1e-16 of the scale, far below
    // the tolerance and far below the gaps of separated integer pairs: same answers, touching
    // pairs included.
    if (hit(mapped(fa, rotated.f), mapped(fb, rotated.f)) != expected) {
      if (++rotatedDisagreements <= 5) ADD_FAILURE() << "rotated disagreement at pair " << i;
    }
  }
  EXPECT_EQ(disagreements, 0);
  EXPECT_EQ(rotatedDisagreements, 0);
  EXPECT_GT(touchingCount, 5000);
  EXPECT_GT(coplanarCount, 30000);
  EXPECT_GT(intersecting, 20000);
  EXPECT_GT(kPairs - intersecting, 20000);
}

// Exact integer predicates for degenerate triangles (segments and points).
std::int64_t orient3d(const I3& a, const I3& b, const I3& c, const I3& d) {
  return dot(cross(sub(b, a), sub(c, a)), sub(d, a));
}

struct I2 {
  std::int64_t x, y;
};
std::int64_t orient2d(const I2& a, const I2& b, const I2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}
bool between(std::int64_t a, std::int64_t b, std::int64_t x) {
  return std::min(a, b) <= x && x <= std::max(a, b);
}
/// Closed 2D segments pq and rs.
bool segSeg2D(const I2& p, const I2& q, const I2& r, const I2& s) {
  const std::int64_t d1 = orient2d(r, s, p), d2 = orient2d(r, s, q), d3 = orient2d(p, q, r),
                     d4 = orient2d(p, q, s);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) {
    return true;
  }
  auto on = [](const I2& a, const I2& b, const I2& x) {
    return between(a.x, b.x, x.x) && between(a.y, b.y, x.y);
  };
  return (d1 == 0 && on(r, s, p)) || (d2 == 0 && on(r, s, q)) || (d3 == 0 && on(p, q, r)) ||
         (d4 == 0 && on(p, q, s));
}
I2 drop(const I3& p, int axis) {
  return axis == 0 ? I2{p[1], p[2]} : (axis == 1 ? I2{p[0], p[2]} : I2{p[0], p[1]});
}
int dominantAxis(const I3& n) {
  const std::int64_t x = std::abs(n[0]), y = std::abs(n[1]), z = std::abs(n[2]);
  return x >= y && x >= z ? 0 : (y >= z ? 1 : 2);
}

struct ISeg {
  I3 p, q;
};

/// The farthest pair of a degenerate (collinear) triangle's vertices.
ISeg hullOf(const ITri& t) {
  ISeg best{t.v[0], t.v[0]};
  std::int64_t len = -1;
  for (int i = 0; i < 3; ++i) {
    const I3 d = sub(t.v[(i + 1) % 3], t.v[i]);
    if (dot(d, d) > len) {
      len = dot(d, d);
      best = {t.v[i], t.v[(i + 1) % 3]};
    }
  }
  return best;
}

/// Closed segment (or point) against a non-degenerate triangle, exactly.
bool exactSegTri(const ISeg& s, const ITri& t) {
  const I3 &a = t.v[0], &b = t.v[1], &c = t.v[2];
  const std::int64_t op = orient3d(a, b, c, s.p), oq = orient3d(a, b, c, s.q);
  if ((op > 0 && oq > 0) || (op < 0 && oq < 0)) return false;
  if (op == 0 && oq == 0) {
    const int ax = dominantAxis(normalOf(t));
    const I2 p = drop(s.p, ax), q = drop(s.q, ax), ta = drop(a, ax), tb = drop(b, ax),
             tc = drop(c, ax);
    auto inside = [&](const I2& x) {
      const std::int64_t o1 = orient2d(ta, tb, x), o2 = orient2d(tb, tc, x),
                         o3 = orient2d(tc, ta, x);
      return !((o1 > 0 || o2 > 0 || o3 > 0) && (o1 < 0 || o2 < 0 || o3 < 0));
    };
    return inside(p) || inside(q) || segSeg2D(p, q, ta, tb) || segSeg2D(p, q, tb, tc) ||
           segSeg2D(p, q, tc, ta);
  }
  // The segment's line meets the plane in one point, inside the segment: which side of each
  // edge is it on?
  const std::int64_t s1 = orient3d(s.p, s.q, a, b), s2 = orient3d(s.p, s.q, b, c),
                     s3 = orient3d(s.p, s.q, c, a);
  return !((s1 > 0 || s2 > 0 || s3 > 0) && (s1 < 0 || s2 < 0 || s3 < 0));
}

bool pointOnSeg(const I3& x, const ISeg& s) {
  const I3 d = sub(s.q, s.p), w = sub(x, s.p);
  if (isZero(d)) return isZero(w);
  return isZero(cross(d, w)) && dot(w, d) >= 0 && dot(sub(x, s.q), d) <= 0;
}

/// Closed segments (or points), exactly.
bool exactSegSeg(const ISeg& s1, const ISeg& s2) {
  const I3 d1 = sub(s1.q, s1.p), d2 = sub(s2.q, s2.p);
  if (isZero(d1)) return pointOnSeg(s1.p, s2);
  if (isZero(d2)) return pointOnSeg(s2.p, s1);
  if (orient3d(s1.p, s1.q, s2.p, s2.q) != 0) return false;  // skew
  const I3 n = cross(d1, d2);
  if (isZero(n)) {  // parallel
    if (!isZero(cross(d1, sub(s2.p, s1.p)))) return false;
    const std::int64_t t0 = dot(d1, sub(s2.p, s1.p)), t1 = dot(d1, sub(s2.q, s1.p));
    return std::max(t0, t1) >= 0 && std::min(t0, t1) <= dot(d1, d1);
  }
  const int ax = dominantAxis(n);
  return segSeg2D(drop(s1.p, ax), drop(s1.q, ax), drop(s2.p, ax), drop(s2.q, ax));
}

/// A random degenerate triangle: a point, a segment with a repeated vertex, or three collinear
/// points (p, p + d, p + k d), vertex order shuffled.
ITri randomDegenerateTriangle(std::mt19937& rng) {
  const int kind = static_cast<int>(rng() % 3);
  const I3 p = randomGridPoint(rng, 4);
  I3 d = randomGridPoint(rng, 3);
  for (std::int64_t& c : d) c -= 1;
  ITri t;
  if (kind == 0) {
    t = {{p, p, p}};
  } else if (kind == 1) {
    const I3 q = randomGridPoint(rng, 4);
    t = {{p, q, q}};
  } else {
    const std::int64_t k = (rng() % 2) ? 2 : -1;
    t = {{p,
          {p[0] + d[0], p[1] + d[1], p[2] + d[2]},
          {p[0] + k * d[0], p[1] + k * d[1], p[2] + k * d[2]}}};
  }
  const int perm = static_cast<int>(rng() % 6);
  return {{t.v[kPerm[perm][0]], t.v[kPerm[perm][1]], t.v[kPerm[perm][2]]}};
}

TEST(TriangleTest, DegenerateRandomIntegerAgainstExactPredicates) {
  std::mt19937 rng(12345);
  int disagreements = 0, intersecting = 0;
  const int kPairs = 60000;
  const Transform rotated = roundingTransforms()[3];
  for (int i = 0; i < kPairs; ++i) {
    const ITri a = randomDegenerateTriangle(rng);
    const bool bDegenerate = rng() % 2 == 0;
    const ITri b =
        bDegenerate ? randomDegenerateTriangle(rng) : randomIntegerTriangle(rng, 0, false);
    const bool expected =
        bDegenerate ? exactSegSeg(hullOf(a), hullOf(b)) : exactSegTri(hullOf(a), b);
    intersecting += expected ? 1 : 0;
    const Tri fa = toTri(a), fb = toTri(b);
    if (hit(fa, fb) != expected || hit(fb, fa) != expected) {
      if (++disagreements <= 5) ADD_FAILURE() << "disagreement at pair " << i;
    }
    if (hit(mapped(fa, rotated.f), mapped(fb, rotated.f)) != expected) {
      if (++disagreements <= 5) ADD_FAILURE() << "rotated disagreement at pair " << i;
    }
  }
  EXPECT_EQ(disagreements, 0);
  EXPECT_GT(intersecting, 5000);
  EXPECT_GT(kPairs - intersecting, 5000);
}

// ---- Symmetry and invariances on random input -------------------------------------------------

TEST(TriangleTest, SymmetryRandomArgumentAndVertexOrder) {
  std::mt19937 rng(12345);
  int asymmetric = 0, intersecting = 0;
  for (int i = 0; i < 3000; ++i) {
    const auto [a, b] = randomPair(rng);
    const int n = countHits(a, b);
    intersecting += n == 72 ? 1 : 0;
    if (n != 0 && n != 72 && ++asymmetric <= 5) ADD_FAILURE() << "pair " << i << ": " << n;
  }
  for (int i = 0; i < 3000; ++i) {  // exact touching configurations are frequent here
    const int mode = static_cast<int>(rng() % 3);
    const ITri a = randomIntegerTriangle(rng, mode, true);
    const ITri b = randomIntegerTriangle(rng, mode, true);
    const int n = countHits(toTri(a), toTri(b));
    if (n != 0 && n != 72 && ++asymmetric <= 5) ADD_FAILURE() << "integer pair " << i;
  }
  EXPECT_EQ(asymmetric, 0);
  EXPECT_GT(intersecting, 300);
}

TEST(TriangleTest, ScaleAndTranslationInvarianceRandomClearMargin) {
  std::mt19937 rng(12345);
  int checked = 0, changed = 0;
  const Vec3 shift(1e5, -1e5, 0.5e5);
  while (checked < 20000) {
    const auto [a, b] = randomPair(rng);
    if (mollerOracle(a, b) == Verdict::Unclear) continue;
    ++checked;
    const bool base = hit(a, b);
    for (const Transform& t :
         {scaling("x1e-3", 1e-3), scaling("x1e3", 1e3),
          Transform{"+1e5", [&](const Vec3& x) -> Vec3 { return x + shift; }}}) {
      if (hit(mapped(a, t.f), mapped(b, t.f)) != base && ++changed <= 5) {
        ADD_FAILURE() << t.name << " changed the answer at case " << checked;
      }
    }
  }
  EXPECT_EQ(changed, 0);
}

TEST(TriangleTest, ScaleAndTranslationInvarianceIntegerTouching) {
  // Exact configurations (many touching); powers of two and integer shifts keep them exact.
  std::mt19937 rng(12345);
  const std::vector<Transform> ts = exactTransforms();
  int changed = 0;
  for (int i = 0; i < 5000; ++i) {
    const int mode = static_cast<int>(rng() % 3);
    const Tri a = toTri(randomIntegerTriangle(rng, mode, true));
    const Tri b = toTri(randomIntegerTriangle(rng, mode, true));
    const bool base = hit(a, b);
    for (const Transform& t : ts) {
      if (hit(mapped(a, t.f), mapped(b, t.f)) != base && ++changed <= 5) {
        ADD_FAILURE() << t.name << " changed the answer at pair " << i;
      }
    }
  }
  EXPECT_EQ(changed, 0);
}

}  // namespace
}  // namespace adb
