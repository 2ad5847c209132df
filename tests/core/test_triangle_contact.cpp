// Tests of triangleContact: known answers (perpendicular piercing, coplanar touching, shallow
// nearly coplanar overlap, edge-edge crossing, hint choice between equal faces), degenerate and
// non-finite input, symmetry, stability under tiny rotations, translation and scale
// invariance, and random intersecting pairs checked for separation after the reported
// translation and against an independent long-double penetration-depth oracle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "adb/core/triangle_contact.h"
#include "adb/core/triangle_test.h"

namespace adb {
namespace {

struct Tri {
  Vec3 v[3];
};

Tri tri(const Vec3& a, const Vec3& b, const Vec3& c) { return Tri{{a, b, c}}; }

TriangleContact contact(const Tri& a, const Tri& b, const Vec3& hint = Vec3::Zero()) {
  return triangleContact(a.v[0], a.v[1], a.v[2], b.v[0], b.v[1], b.v[2], hint);
}

bool hit(const Tri& a, const Tri& b) {
  return trianglesIntersect(a.v[0], a.v[1], a.v[2], b.v[0], b.v[1], b.v[2]);
}

Tri moved(const Tri& t, const Vec3& d) { return tri(t.v[0] + d, t.v[1] + d, t.v[2] + d); }

/// Largest extent along x, y or z of the six vertices (the scale of the configuration).
double scaleOf(const Tri& a, const Tri& b) {
  Vec3 lo = a.v[0], hi = a.v[0];
  for (const Tri* t : {&a, &b}) {
    for (const Vec3& p : t->v) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    }
  }
  return (hi - lo).maxCoeff();
}

double angle(const Vec3& u, const Vec3& v) { return std::atan2(u.cross(v).norm(), u.dot(v)); }

bool finite(const TriangleContact& c) {
  return c.pointOnB.allFinite() && c.normal.allFinite() && std::isfinite(c.depth);
}

/// Distance from p to the closed triangle t: the smaller of the distances to its three edges and,
/// when p projects inside, to its plane. (Ericson's Voronoi-region version loses all accuracy
/// on slivers; here a wrong inside decision near an edge is covered by the edge distance.)
double distanceToTriangle(const Vec3& p, const Tri& t) {
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const Vec3 &s = t.v[i], &e = t.v[(i + 1) % 3];
    const Vec3 d = e - s;
    const double l = d.squaredNorm();
    const double u = l > 0 ? std::clamp((p - s).dot(d) / l, 0.0, 1.0) : 0.0;
    best = std::min(best, (p - (s + u * d)).norm());
  }
  const Vec3 n = (t.v[1] - t.v[0]).cross(t.v[2] - t.v[0]);
  const double nn = n.squaredNorm();
  if (nn > 0) {
    bool inside = true;
    for (int i = 0; i < 3; ++i) {
      inside = inside && (t.v[(i + 1) % 3] - t.v[i]).cross(p - t.v[i]).dot(n) >= 0;
    }
    if (inside) best = std::min(best, std::abs(n.dot(p - t.v[0])) / std::sqrt(nn));
  }
  return best;
}

/// Translating B by normal * (depth + margin) separates the triangles.
bool separatesAfterMove(const Tri& a, const Tri& b, const TriangleContact& c, double margin) {
  return !hit(a, moved(b, c.normal * (c.depth + margin)));
}

Mat3 rotation(double radians, const Vec3& axis) {
  return Eigen::AngleAxisd(radians, axis.normalized()).toRotationMatrix();
}

Tri rotatedAbout(const Tri& t, const Mat3& r, const Vec3& centre) {
  return tri(r * (t.v[0] - centre) + centre, r * (t.v[1] - centre) + centre,
             r * (t.v[2] - centre) + centre);
}

Vec3 centroid(const Tri& t) { return (t.v[0] + t.v[1] + t.v[2]) / 3.0; }

const Vec3 kUp(0, 0, 1);

// A large ground triangle in z = 0, counter-clockwise seen from +z (normal +z).
const Tri kGround = tri(Vec3(-2, -2, 0), Vec3(4, -2, 0), Vec3(-2, 4, 0));

// ---- Known answers ---------------------------------------------------------------------------

TEST(TriangleContactFace, PerpendicularPiercingHasTheFaceNormalAndExactDepth) {
  // B stands vertically in the plane y = 0 and its lowest vertex is 0.3 below A's plane.
  const Tri b = tri(Vec3(0, 0, -0.3), Vec3(0.5, 0, 1), Vec3(-0.5, 0, 1));
  ASSERT_TRUE(hit(kGround, b));
  const TriangleContact c = contact(kGround, b);
  ASSERT_TRUE(c.valid);
  EXPECT_LT((c.normal - kUp).norm(), 1e-12);
  EXPECT_NEAR(c.depth, 0.3, 1e-12);
  EXPECT_LT((c.pointOnB - Vec3(0, 0, -0.3)).norm(), 1e-12);  // B's piercing vertex

  // A's winding does not matter: the face axis is used in both orientations.
  const Tri flipped = tri(kGround.v[0], kGround.v[2], kGround.v[1]);
  const TriangleContact f = contact(flipped, b);
  EXPECT_LT((f.normal - kUp).norm(), 1e-12);
  EXPECT_NEAR(f.depth, 0.3, 1e-12);
}

TEST(TriangleContactFace, DeepPiercingFollowsTheHint) {
  // 0.7 below and 0.3 above: the minimum translation pushes B down through A, the hint (say
  // the previous frame's normal) keeps it on its side.
  const Tri b = tri(Vec3(0, 0, -0.7), Vec3(0.5, 0, 0.3), Vec3(-0.5, 0, 0.3));
  const TriangleContact free = contact(kGround, b);
  EXPECT_LT((free.normal + kUp).norm(), 1e-12);
  EXPECT_NEAR(free.depth, 0.3, 1e-12);
  const TriangleContact hinted = contact(kGround, b, Vec3(0.2, 0.1, 3.0));
  EXPECT_LT((hinted.normal - kUp).norm(), 1e-12);
  EXPECT_NEAR(hinted.depth, 0.7, 1e-12);
  EXPECT_LT((hinted.pointOnB - Vec3(0, 0, -0.7)).norm(), 1e-12);
}

TEST(TriangleContactFace, VertexOfAPiercingBUsesBsNormal) {
  // Roles swapped: A's vertex is 0.25 into B's plane (x = 0), B must move along +x.
  const Tri b = tri(Vec3(0, -2, -2), Vec3(0, 4, -2), Vec3(0, -2, 4));
  const Tri a = tri(Vec3(0.25, 0, 0), Vec3(-1, 0.5, 0), Vec3(-1, -0.5, 0.2));
  ASSERT_TRUE(hit(a, b));
  const TriangleContact c = contact(a, b);
  EXPECT_LT((c.normal - Vec3(1, 0, 0)).norm(), 1e-12);
  EXPECT_NEAR(c.depth, 0.25, 1e-12);
  EXPECT_LT((c.pointOnB - Vec3(0, 0, 0)).norm(), 1e-12);  // A's vertex dropped onto B
}

TEST(TriangleContactFace, CoplanarTouchingHasDepthZeroAndTheHintsSide) {
  const Tri b = tri(Vec3(0.2, 0.2, 0), Vec3(0.8, 0.2, 0), Vec3(0.2, 0.8, 0));
  ASSERT_TRUE(hit(kGround, b));
  for (const Vec3& hint : {Vec3(0, 0, 1), Vec3(0.3, -0.2, 1), Vec3(0, 0, 1e-30)}) {
    const TriangleContact c = contact(kGround, b, hint);
    ASSERT_TRUE(c.valid);
    EXPECT_EQ(c.depth, 0.0);
    EXPECT_EQ(c.normal, kUp);
    EXPECT_LT(distanceToTriangle(c.pointOnB, b), 1e-15);
  }
  const TriangleContact down = contact(kGround, b, Vec3(0.1, 0, -2));
  EXPECT_EQ(down.depth, 0.0);
  EXPECT_EQ(down.normal, -kUp);
  // No hint: the larger triangle's winding decides (A's +n here)...
  EXPECT_EQ(contact(kGround, b).normal, kUp);
  // ...and when B is the larger one, B's -n: B wound like A (normal +z) moves down.
  EXPECT_EQ(contact(b, kGround).normal, -kUp);
  // Partial overlap and a shared edge are touching too.
  const Tri half = tri(Vec3(-3, 0, 0), Vec3(1, 0, 0), Vec3(-3, 1, 0));
  EXPECT_EQ(contact(kGround, half, kUp).depth, 0.0);
  EXPECT_EQ(contact(kGround, half, kUp).normal, kUp);
  const Tri beside = tri(Vec3(4, -2, 0), Vec3(-2, 4, 0), Vec3(4, 4, 0));
  EXPECT_EQ(contact(kGround, beside, kUp).depth, 0.0);
  EXPECT_EQ(contact(kGround, beside, kUp).normal, kUp);
}

TEST(TriangleContactFace, ShallowNearlyCoplanarOverlapTakesTheVerticalDepth) {
  // B lies over A (horizontal overlaps ~4) but is tilted by ~1e-3 and dips 0.001 below A's
  // plane: the depth is 0.001 along A's normal. (A's corners are 0.003 below B's plane, so B's
  // face needs more; with A only 4 wide they would be 0.001 below it, an equally deep face.)
  const Tri a = tri(Vec3(0, 0, 0), Vec3(6, 0, 0), Vec3(0, 6, 0));
  const Tri b = tri(Vec3(1, 1, -0.001), Vec3(5, 1, 0.003), Vec3(1, 5, 0.003));
  ASSERT_TRUE(hit(a, b));
  const TriangleContact c = contact(a, b);
  EXPECT_LT((c.normal - kUp).norm(), 1e-12);
  EXPECT_NEAR(c.depth, 0.001, 1e-12);
  EXPECT_LT(distanceToTriangle(c.pointOnB, b), 1e-12);
  // Same with the whole configuration tilted and a hint from either side of the plane.
  const Mat3 r = rotation(0.7, Vec3(1, 2, 3));
  const Tri ra = rotatedAbout(a, r, Vec3::Zero()), rb = rotatedAbout(b, r, Vec3::Zero());
  const TriangleContact h = contact(ra, rb, r * Vec3(0.5, 0, 1));
  EXPECT_LT((h.normal - r * kUp).norm(), 1e-12);
  EXPECT_NEAR(h.depth, 0.001, 1e-12);
}

TEST(TriangleContactEdge, CrossingEdgesGiveTheirCommonPerpendicular) {
  // A's top edge runs along x at height 0.1, B's bottom edge along y at height 0; A extends
  // down, B up. The faces need >= 0.67 to separate, the edges 0.1 along z.
  const Tri a = tri(Vec3(-1, 0, 0.1), Vec3(1, 0, 0.1), Vec3(0, -1, -1));
  const Tri b = tri(Vec3(0, -1, 0), Vec3(0, 1, 0), Vec3(1, 0, 1));
  ASSERT_TRUE(hit(a, b));
  const TriangleContact c = contact(a, b);
  ASSERT_TRUE(c.valid);
  EXPECT_LT((c.normal - kUp).norm(), 1e-12);
  EXPECT_LT(std::abs(c.normal.dot(Vec3(1, 0, 0))) + std::abs(c.normal.dot(Vec3(0, 1, 0))), 1e-12);
  EXPECT_NEAR(c.depth, 0.1, 1e-12);
  EXPECT_LT((c.pointOnB - Vec3(0, 0, 0)).norm(), 1e-12);  // where the edges cross (from above)

  // An oblique version: edges along random directions, same construction.
  const Vec3 e(0.6, -0.3, 0.2), f(0.1, 0.7, -0.4);
  const Vec3 n = e.cross(f).normalized();
  const Vec3 mid(0.3, 0.2, -0.1);
  const Tri ta = tri(mid - e + 0.05 * n, mid + e + 0.05 * n, mid - 0.8 * n + 0.3 * f);
  const Tri tb = tri(mid - f - 0.05 * n, mid + f - 0.05 * n, mid + 0.9 * n + 0.4 * e);
  ASSERT_TRUE(hit(ta, tb));
  const TriangleContact o = contact(ta, tb);
  EXPECT_LT((o.normal - n).norm(), 1e-12);
  EXPECT_NEAR(o.depth, 0.1, 1e-12);
  EXPECT_LT(std::abs(o.normal.dot(e)) + std::abs(o.normal.dot(f)), 1e-12);
  EXPECT_TRUE(separatesAfterMove(ta, tb, o, 1e-9));
}

TEST(TriangleContactHint, ChoosesBetweenEquallyDeepFaces) {
  // A (z = 0) pokes 0.2 through B's plane (x = 0) and B pokes 0.2 through A's plane: +z (A's
  // face) and +x (B's face) both need exactly 0.2.
  const double d = 0.2;
  // The tips are blunt so that no edge-edge axis is shallower (with sharp tips, the tips'
  // edges cross each other and an edge axis needs only ~0.18).
  const Tri a = tri(Vec3(-1, -2, 0), Vec3(-1, 2, 0), Vec3(d, 0, 0));
  const Tri b = tri(Vec3(0, -1, 1), Vec3(0, 1, 1), Vec3(0, 0, -d));
  ASSERT_TRUE(hit(a, b));
  const TriangleContact up = contact(a, b, Vec3(0, 0, 1));
  EXPECT_LT((up.normal - kUp).norm(), 1e-12);
  EXPECT_NEAR(up.depth, d, 1e-12);
  const TriangleContact side = contact(a, b, Vec3(1, 0, 0));
  EXPECT_LT((side.normal - Vec3(1, 0, 0)).norm(), 1e-12);
  EXPECT_NEAR(side.depth, d, 1e-12);
  // A hint slightly closer to one face picks it.
  EXPECT_LT((contact(a, b, Vec3(1, 0, 0.9)).normal - Vec3(1, 0, 0)).norm(), 1e-12);
  EXPECT_LT((contact(a, b, Vec3(0.9, 0.1, 1)).normal - kUp).norm(), 1e-12);
  // No hint, or a hint equally close to both: the larger triangle (A) wins.
  EXPECT_LT((contact(a, b).normal - kUp).norm(), 1e-12);
  EXPECT_LT((contact(a, b, Vec3(1, 0, 1)).normal - kUp).norm(), 1e-12);
  // Swapped roles (hint reversed too): same choice, negated.
  EXPECT_LT((contact(b, a, Vec3(-1, 0, 0)).normal + Vec3(1, 0, 0)).norm(), 1e-12);
  EXPECT_LT((contact(b, a, Vec3(0, 0, -1)).normal + kUp).norm(), 1e-12);
  // Faces within the tie band (0.1 %) are still chosen by the hint: hysteresis.
  const Tri b2 = tri(Vec3(0, -1, 1), Vec3(0, 1, 1), Vec3(0, 0, -d * (1 + 2e-4)));
  EXPECT_LT((contact(a, b2, Vec3(1, 0, 0)).normal - Vec3(1, 0, 0)).norm(), 1e-12);
  EXPECT_LT((contact(a, b2, Vec3(0, 0, 1)).normal - kUp).norm(), 1e-12);
}

// ---- Degenerate and non-finite input ---------------------------------------------------------

TEST(TriangleContactDegenerate, SegmentPointAndNonFiniteInput) {
  // B a segment (repeated vertex) piercing A: A's normal, exact depth.
  const Tri seg = tri(Vec3(0.1, 0.2, -0.4), Vec3(0.3, 0.1, 1.0), Vec3(0.3, 0.1, 1.0));
  const TriangleContact s = contact(kGround, seg);
  ASSERT_TRUE(s.valid);
  EXPECT_LT((s.normal - kUp).norm(), 1e-12);
  EXPECT_NEAR(s.depth, 0.4, 1e-12);
  EXPECT_LT((s.pointOnB - Vec3(0.1, 0.2, -0.4)).norm(), 1e-12);
  // Collinear (not repeated) vertices: the same.
  const Tri line = tri(Vec3(0.1, 0.2, -0.4), Vec3(0.2, 0.15, 0.3), Vec3(0.3, 0.1, 1.0));
  const TriangleContact l = contact(kGround, line);
  EXPECT_LT((l.normal - kUp).norm(), 1e-12);
  EXPECT_NEAR(l.depth, 0.4, 1e-12);
  // A degenerate, B not: B's normal.
  const TriangleContact r = contact(line, kGround);
  EXPECT_LT((r.normal + kUp).norm(), 1e-12);
  EXPECT_NEAR(r.depth, 0.4, 1e-12);

  // B a point on A: A's normal, depth 0.
  const Vec3 p(0.5, 0.5, 0);
  const TriangleContact pt = contact(kGround, tri(p, p, p));
  ASSERT_TRUE(pt.valid);
  EXPECT_EQ(pt.normal, kUp);
  EXPECT_EQ(pt.depth, 0.0);
  EXPECT_EQ(pt.pointOnB, p);

  // Two crossing segments: their common perpendicular, depth 0.
  const Tri sa = tri(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(1, 0, 0));
  const Tri sb = tri(Vec3(0, -1, 0), Vec3(0, 1, 0), Vec3(0, 0.5, 0));
  ASSERT_TRUE(hit(sa, sb));
  const TriangleContact x = contact(sa, sb);
  ASSERT_TRUE(x.valid);
  EXPECT_LT(std::abs(std::abs(x.normal.z()) - 1), 1e-12);
  EXPECT_EQ(x.depth, 0.0);
  EXPECT_LT((contact(sa, sb, -kUp).normal + kUp).norm(), 1e-12);

  // Two collinear overlapping segments, and two coincident points: no direction without a
  // hint, the hint with one.
  const Tri ca = tri(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 0, 0));
  const Tri cb = tri(Vec3(1, 0, 0), Vec3(3, 0, 0), Vec3(3, 0, 0));
  ASSERT_TRUE(hit(ca, cb));
  const TriangleContact none = contact(ca, cb);
  EXPECT_FALSE(none.valid);
  EXPECT_TRUE(finite(none));
  EXPECT_EQ(none.normal, Vec3::Zero());
  EXPECT_EQ(none.depth, 0.0);
  const TriangleContact withHint = contact(ca, cb, Vec3(0, 2, 0));
  ASSERT_TRUE(withHint.valid);
  EXPECT_EQ(withHint.normal, Vec3(0, 1, 0));
  EXPECT_EQ(withHint.depth, 0.0);
  const Tri point = tri(Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(1, 2, 3));
  EXPECT_FALSE(contact(point, point).valid);
  EXPECT_TRUE(finite(contact(point, point)));
  EXPECT_TRUE(contact(point, point, Vec3(1, 1, 0)).valid);
  EXPECT_NEAR(contact(point, point, Vec3(1, 1, 0)).normal.norm(), 1.0, 1e-15);

  // Non-finite coordinates: invalid, finite output. A non-finite hint is ignored.
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Tri b = tri(Vec3(0, 0, -0.3), Vec3(0.5, 0, 1), Vec3(-0.5, 0, 1));
  for (const double bad : {inf, -inf, nan}) {
    for (int k = 0; k < 6; ++k) {
      Tri ta = kGround, tb = b;
      (k < 3 ? ta.v[k] : tb.v[k - 3]).y() = bad;
      const TriangleContact c = contact(ta, tb, kUp);
      EXPECT_FALSE(c.valid);
      EXPECT_TRUE(finite(c));
    }
    const TriangleContact h = contact(kGround, b, Vec3(0, bad, 1));
    ASSERT_TRUE(h.valid);
    EXPECT_TRUE(finite(h));
    EXPECT_LT((h.normal - kUp).norm(), 1e-12);
  }

  // Extreme magnitudes stay finite and scale along.
  for (const double k : {1e-300, 1e300, 0x1p-1070}) {
    const Tri ta = tri(k * kGround.v[0], k * kGround.v[1], k * kGround.v[2]);
    const Tri tb = tri(k * b.v[0], k * b.v[1], k * b.v[2]);
    const TriangleContact c = contact(ta, tb);
    ASSERT_TRUE(c.valid) << k;
    EXPECT_TRUE(finite(c)) << k;
    EXPECT_LT((c.normal - kUp).norm(), 1e-12) << k;
    if (k > 1e-300) {
      EXPECT_NEAR(c.depth / k, 0.3, 1e-12) << k;
    }
  }
  // Coordinates near DBL_MAX (differences overflow): same answer as at scale 1.
  const Tri ua = tri(Vec3(-1, -1, 0), Vec3(1, -1, 0), Vec3(-1, 1, 0));
  const Tri ub = tri(Vec3(0, 0, -0.5), Vec3(1, 0, 1), Vec3(-1, 0, 1));
  const double big = std::numeric_limits<double>::max() / 3;
  const TriangleContact unit = contact(ua, ub);
  const TriangleContact huge = contact(tri(big * ua.v[0], big * ua.v[1], big * ua.v[2]),
                                       tri(big * ub.v[0], big * ub.v[1], big * ub.v[2]));
  EXPECT_TRUE(huge.valid);
  EXPECT_TRUE(finite(huge));
  EXPECT_LT((huge.normal - unit.normal).norm(), 1e-12);
  EXPECT_NEAR(huge.depth / big, unit.depth, 1e-12);
}

// ---- Symmetry, stability, invariance ---------------------------------------------------------

/// Configurations with a clear winner (no exact area tie), for the invariance tests.
std::vector<std::pair<Tri, Tri>> namedConfigurations() {
  return {
      {kGround, tri(Vec3(0, 0, -0.3), Vec3(0.5, 0, 1), Vec3(-0.5, 0, 1))},
      {kGround, tri(Vec3(0.1, -0.2, -0.3), Vec3(0.6, 0.1, 1), Vec3(-0.5, 0.3, 0.9))},
      {tri(Vec3(0, 0, 0), Vec3(6, 0, 0), Vec3(0, 6, 0)),
       tri(Vec3(1, 1, -0.001), Vec3(5, 1, 0.003), Vec3(1, 5, 0.003))},
      {tri(Vec3(-1, 0, 0.1), Vec3(1, 0, 0.1), Vec3(0, -1, -1)),
       tri(Vec3(0, -1, 0), Vec3(0, 1, 0), Vec3(1, 0, 1))},
      {tri(Vec3(0.25, 0, 0), Vec3(-1, 0.5, 0), Vec3(-1, -0.5, 0.2)),
       tri(Vec3(0, -2, -2), Vec3(0, 4, -2), Vec3(0, -2, 4))},
  };
}

TEST(TriangleContactSymmetry, SwappingNegatesTheNormalAndKeepsTheDepth) {
  for (const auto& [a, b] : namedConfigurations()) {
    for (const Vec3& hint : {Vec3(0, 0, 0), Vec3(0.2, -0.1, 1), Vec3(1, 0.3, -0.2)}) {
      const TriangleContact ab = contact(a, b, hint), ba = contact(b, a, -hint);
      EXPECT_LT((ab.normal + ba.normal).norm(), 1e-12);
      EXPECT_NEAR(ab.depth, ba.depth, 1e-12);
      // pointOnB of the swapped call is the matching point on (the original) A.
      EXPECT_TRUE(separatesAfterMove(a, b, ab, 1e-9));
      EXPECT_TRUE(separatesAfterMove(b, a, ba, 1e-9));
    }
  }
  // And vertex order does not matter either.
  for (const auto& [a, b] : namedConfigurations()) {
    const TriangleContact ref = contact(a, b);
    const TriangleContact perm = contact(tri(a.v[1], a.v[2], a.v[0]), tri(b.v[2], b.v[0], b.v[1]));
    EXPECT_LT((ref.normal - perm.normal).norm(), 1e-12);
    EXPECT_NEAR(ref.depth, perm.depth, 1e-12);
  }
}

TEST(TriangleContactStability, TinyRotationsOfBMoveFaceNormalsByTheRotationOnly) {
  std::mt19937 rng(12345);
  std::normal_distribution<double> gauss;
  struct Case {
    Tri a, b;
    Vec3 hint;
  };
  const Case cases[] = {
      // B's vertex into A (A's normal), tilted, hint or not.
      {kGround, tri(Vec3(0.1, -0.2, -0.3), Vec3(0.6, 0.1, 1), Vec3(-0.5, 0.3, 0.9)), Vec3::Zero()},
      {kGround, tri(Vec3(0.1, -0.2, -0.3), Vec3(0.6, 0.1, 1), Vec3(-0.5, 0.3, 0.9)), kUp},
      // A's vertex into B (B's normal, which turns with B).
      {tri(Vec3(0.25, 0, 0), Vec3(-1, 0.5, 0), Vec3(-1, -0.5, 0.2)),
       tri(Vec3(0, -2, -2), Vec3(0, 4, -2), Vec3(0, -2, 4)), Vec3::Zero()},
      // Resting: B nearly flat on A (tilt 1e-3, 1e-4 deep), hint = previous normal.
      {kGround, tri(Vec3(0, 0, -1e-4), Vec3(1, 0, 9e-4), Vec3(0, 1, 9e-4)), kUp},
      // Resting exactly flat (depth 0) with the hint.
      {kGround, tri(Vec3(0, 0, 0), Vec3(1, 0.1, 0), Vec3(0.2, 1, 0)), kUp},
  };
  double worstAngle = 0, worstDepthChange = 0;
  for (const Case& k : cases) {
    ASSERT_TRUE(hit(k.a, k.b));
    const TriangleContact ref = contact(k.a, k.b, k.hint);
    ASSERT_TRUE(ref.valid);
    for (int trial = 0; trial < 200; ++trial) {
      const Vec3 axis(gauss(rng), gauss(rng), gauss(rng));
      const Tri rb = rotatedAbout(k.b, rotation(1e-6, axis), centroid(k.b));
      if (!hit(k.a, rb)) continue;  // the flat case can lift off
      const TriangleContact c = contact(k.a, rb, k.hint);
      ASSERT_TRUE(c.valid);
      worstAngle = std::max(worstAngle, angle(ref.normal, c.normal));
      worstDepthChange = std::max(worstDepthChange, std::abs(c.depth - ref.depth));
    }
  }
  std::printf("[ stability] 1e-6 rad rotations: worst normal change %.3g rad, depth change %.3g\n",
              worstAngle, worstDepthChange);
  EXPECT_LE(worstAngle, 1e-5);
  EXPECT_LE(worstDepthChange, 1e-5);  // B's size ~ 2: a 1e-6 rotation moves points by ~2e-6
}

TEST(TriangleContactStability, RandomFaceContactsRarelySwitch) {
  // Random intersecting pairs whose normal is a face normal: after a 1e-6 rad rotation of B the
  // normal moves by at most ~1e-6 unless the pair sits within ~1e-6 of a switching point
  // between two candidates (a measure-zero set, thin for a tiny rotation).
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss;
  const auto point = [&] { return Vec3(unit(rng), unit(rng), unit(rng)); };
  int faces = 0, steady = 0;
  double worstDepthJump = 0;
  for (int attempt = 0; attempt < 200000 && faces < 5000; ++attempt) {
    const Tri a = tri(point(), point(), point()), b = tri(point(), point(), point());
    if (!hit(a, b)) continue;
    const TriangleContact ref = contact(a, b);
    const Vec3 na = (a.v[1] - a.v[0]).cross(a.v[2] - a.v[0]).normalized();
    const Vec3 nb = (b.v[1] - b.v[0]).cross(b.v[2] - b.v[0]).normalized();
    if (std::abs(ref.normal.dot(na)) < 1 - 1e-12 && std::abs(ref.normal.dot(nb)) < 1 - 1e-12) {
      continue;
    }
    const Tri rb =
        rotatedAbout(b, rotation(1e-6, Vec3(gauss(rng), gauss(rng), gauss(rng))), centroid(b));
    if (!hit(a, rb)) continue;
    ++faces;
    const TriangleContact c = contact(a, rb);
    if (angle(ref.normal, c.normal) <= 1e-5) {
      ++steady;
      worstDepthJump = std::max(worstDepthJump, std::abs(c.depth - ref.depth));
    }
  }
  std::printf(
      "[ stability] random face contacts: %d / %d keep their normal within 1e-5 rad "
      "(worst depth change then %.3g)\n",
      steady, faces, worstDepthJump);
  EXPECT_GE(steady, 0.999 * faces);
  EXPECT_LE(worstDepthJump, 1e-5);
}

TEST(TriangleContactInvariance, TranslationAndScaling) {
  for (const auto& [a, b] : namedConfigurations()) {
    const TriangleContact ref = contact(a, b, Vec3(0.1, 0.2, 1));
    const Vec3 t(1e5, -3e5, 7e4);
    const TriangleContact tr = contact(moved(a, t), moved(b, t), Vec3(0.1, 0.2, 1));
    EXPECT_LT((tr.normal - ref.normal).norm(), 1e-9);
    EXPECT_NEAR(tr.depth, ref.depth, 1e-9);
    EXPECT_LT((tr.pointOnB - t - ref.pointOnB).norm(), 1e-9);
    for (const double s : {1e-3, 1e3}) {
      const Tri sa = tri(s * a.v[0], s * a.v[1], s * a.v[2]);
      const Tri sb = tri(s * b.v[0], s * b.v[1], s * b.v[2]);
      const TriangleContact c = contact(sa, sb, Vec3(0.1, 0.2, 1));
      EXPECT_LT((c.normal - ref.normal).norm(), 1e-12) << s;
      EXPECT_NEAR(c.depth / s, ref.depth, 1e-12) << s;
      EXPECT_LT((c.pointOnB / s - ref.pointOnB).norm(), 1e-12) << s;
    }
    // Powers of two: bit-exact.
    const double p = 0x1p-20;
    const TriangleContact c = contact(tri(p * a.v[0], p * a.v[1], p * a.v[2]),
                                      tri(p * b.v[0], p * b.v[1], p * b.v[2]), Vec3(0.1, 0.2, 1));
    EXPECT_EQ(c.normal, ref.normal);
    EXPECT_EQ(c.depth, p * ref.depth);
    EXPECT_EQ(c.pointOnB, p * ref.pointOnB);
  }
}

// ---- Random pairs ----------------------------------------------------------------------------

/// Independent oracle: the penetration depth as the minimum, over the complete candidate set
/// (both face normals, the nine edge-edge cross products, both orientations), of the overlap of
/// the projections, in long double. Axes are not filtered, only zero ones skipped.
double oracleDepth(const Tri& a, const Tri& b) {
  using V = Eigen::Matrix<long double, 3, 1>;
  V pa[3], pb[3];
  for (int i = 0; i < 3; ++i) {
    pa[i] = a.v[i].cast<long double>();
    pb[i] = b.v[i].cast<long double>();
  }
  V axes[11];
  int n = 0;
  axes[n++] = (pa[1] - pa[0]).cross(pa[2] - pa[0]);
  axes[n++] = (pb[1] - pb[0]).cross(pb[2] - pb[0]);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      axes[n++] = (pa[(i + 1) % 3] - pa[i]).cross(pb[(j + 1) % 3] - pb[j]);
    }
  }
  long double best = std::numeric_limits<long double>::infinity();
  for (const V& axis : axes) {
    const long double len = axis.norm();
    if (!(len > 0)) continue;
    const V u = axis / len;
    long double loA = pa[0].dot(u), hiA = loA, loB = pb[0].dot(u), hiB = loB;
    for (int i = 1; i < 3; ++i) {
      loA = std::min(loA, pa[i].dot(u));
      hiA = std::max(hiA, pa[i].dot(u));
      loB = std::min(loB, pb[i].dot(u));
      hiB = std::max(hiB, pb[i].dot(u));
    }
    best = std::min(best, std::min(hiA - loB, hiB - loA));
  }
  return static_cast<double>(best);
}

struct Stats {
  int pairs = 0, separated = 0, pointInB = 0, minimal = 0, pointOnA = 0;
};

void report(const char* name, const Stats& s) {
  std::printf(
      "[  random  ] %-16s %6d pairs: separated %.4f %%, pointOnB in B %.4f %%, "
      "depth within bias of oracle %.4f %%, pointOnB+depth*n near A %.4f %%\n",
      name, s.pairs, 100.0 * s.separated / s.pairs, 100.0 * s.pointInB / s.pairs,
      100.0 * s.minimal / s.pairs, 100.0 * s.pointOnA / s.pairs);
}

/// Shared checks of one random intersecting pair.
void checkRandom(const Tri& a, const Tri& b, const Vec3& hint, Stats& s) {
  const TriangleContact c = contact(a, b, hint);
  ASSERT_TRUE(c.valid);
  ASSERT_TRUE(finite(c));
  ASSERT_NEAR(c.normal.norm(), 1.0, 1e-12);
  ASSERT_GE(c.depth, 0.0);
  const double scale = scaleOf(a, b);
  ++s.pairs;
  s.separated += separatesAfterMove(a, b, c, 1e-9 * scale) ? 1 : 0;
  s.pointInB += distanceToTriangle(c.pointOnB, b) <= 1e-10 * scale ? 1 : 0;
  s.pointOnA += distanceToTriangle(c.pointOnB + c.depth * c.normal, a) <= 1e-3 * scale ? 1 : 0;
  // Without a hint the depth is the penetration depth up to the edge bias (5 %) and the tie
  // band (0.1 % + 1e-9 L); it can never be below it (every axis over-estimates). With a hint
  // only the lower bound holds (the hint may impose a deeper orientation).
  const double pd = oracleDepth(a, b);
  const bool lower = c.depth >= pd - 1e-12 * scale;
  const bool upper = c.depth <= 1.05 * 1.001 * std::max(pd, 0.0) + 2e-9 * scale;
  s.minimal += (hint == Vec3::Zero() ? lower && upper : lower) ? 1 : 0;
}

TEST(TriangleContactRandom, IntersectingPairsSeparateAfterTheReportedTranslation) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> gauss;
  const auto point = [&] { return Vec3(unit(rng), unit(rng), unit(rng)); };
  const auto direction = [&] { return Vec3(gauss(rng), gauss(rng), gauss(rng)).normalized(); };

  // Generic: six uniform vertices in the unit cube.
  Stats generic, hinted, flat, shared;
  int attempts = 0;
  while (generic.pairs < 20000 && attempts < 400000) {
    ++attempts;
    const Tri a = tri(point(), point(), point()), b = tri(point(), point(), point());
    if (!hit(a, b)) continue;
    checkRandom(a, b, Vec3::Zero(), generic);
    if (generic.pairs % 4 == 0) checkRandom(a, b, direction(), hinted);
  }
  // Nearly coplanar: B drawn in A's plane, then tilted by 1e-8 .. 1e-2 rad and offset off the
  // plane by up to 1e-3 (tiny depths, the hard case for separation).
  std::uniform_real_distribution<double> logAngle(-8, -2);
  while (flat.pairs < 3000 && attempts < 800000) {
    ++attempts;
    const Tri a = tri(point(), point(), point());
    const Vec3 n = (a.v[1] - a.v[0]).cross(a.v[2] - a.v[0]).normalized();
    const Vec3 u = (a.v[1] - a.v[0]).normalized(), w = n.cross(u);
    Tri b;
    for (Vec3& p : b.v) p = a.v[0] + (unit(rng) * 1.2 - 0.1) * u + (unit(rng) * 1.2 - 0.1) * w;
    b = rotatedAbout(b, rotation(std::pow(10.0, logAngle(rng)), direction()), centroid(b));
    b = moved(b, n * (unit(rng) - 0.5) * 2e-3);
    if (!hit(a, b)) continue;
    checkRandom(a, b, Vec3::Zero(), flat);
  }
  // Mesh neighbours: B shares a vertex of A (depth often 0 or tiny).
  while (shared.pairs < 3000 && attempts < 1200000) {
    ++attempts;
    const Tri a = tri(point(), point(), point());
    const Tri b = tri(a.v[0], point(), point());
    if (!hit(a, b)) continue;
    checkRandom(a, b, Vec3::Zero(), shared);
  }
  // Degenerate or sliver B through a point of A: a segment (repeated vertex), or a triangle
  // whose third vertex is 10^-14 .. 10^-6 off the line of the other two.
  std::uniform_real_distribution<double> logHeight(-14, -6);
  Stats sliver;
  while (sliver.pairs < 3000 && attempts < 1600000) {
    ++attempts;
    const Tri a = tri(point(), point(), point());
    const double u = unit(rng), w = unit(rng) * (1 - u);
    const Vec3 through = a.v[0] + u * (a.v[1] - a.v[0]) + w * (a.v[2] - a.v[0]);
    const Vec3 d = direction();
    const Vec3 p = through - unit(rng) * 0.5 * d, q = through + unit(rng) * 0.5 * d;
    const Vec3 off = d.cross(direction()).normalized();
    const Vec3 third =
        sliver.pairs % 2 == 0 ? q : p + unit(rng) * (q - p) + std::pow(10.0, logHeight(rng)) * off;
    const Tri b = tri(p, q, third);
    if (!hit(a, b)) continue;
    checkRandom(a, b, Vec3::Zero(), sliver);
  }
  report("generic", generic);
  report("generic+hint", hinted);
  report("nearly coplanar", flat);
  report("shared vertex", shared);
  report("segment/sliver B", sliver);
  for (const Stats* s : {&generic, &hinted, &flat, &shared, &sliver}) {
    EXPECT_GE(s->separated, 0.999 * s->pairs);
    EXPECT_GE(s->pointInB, 0.999 * s->pairs);
    EXPECT_GE(s->minimal, 0.999 * s->pairs);
  }
  EXPECT_EQ(generic.pairs, 20000);
}

TEST(TriangleContactRandom, SwappingIsSymmetric) {
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const auto point = [&] { return Vec3(unit(rng), unit(rng), unit(rng)); };
  int pairs = 0, symmetric = 0;
  for (int attempt = 0; attempt < 100000 && pairs < 5000; ++attempt) {
    const Tri a = tri(point(), point(), point()), b = tri(point(), point(), point());
    if (!hit(a, b)) continue;
    ++pairs;
    const TriangleContact ab = contact(a, b), ba = contact(b, a);
    symmetric += (ab.normal + ba.normal).norm() <= 1e-12 && std::abs(ab.depth - ba.depth) <= 1e-12;
  }
  std::printf("[  random  ] swap symmetry %d / %d\n", symmetric, pairs);
  EXPECT_GE(symmetric, 0.999 * pairs);
}

}  // namespace
}  // namespace adb
