// Sphere, capsule and box against a triangle, in closed form: known answers, a sampling
// oracle for distances, the exact triangle test as the oracle for box overlap, and the
// oriented-box tree query against brute force.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "adb/core/box_query.h"
#include "adb/support/mesh_generators.h"
#include "adb/core/primitive_contact.h"
#include "adb/core/tree.h"
#include "adb/core/triangle_test.h"
#include "test_support.h"

namespace adb {
namespace {

Vec3 randomPoint(std::mt19937_64& rng, double scale) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return Vec3(u(rng), u(rng), u(rng));
}

Mat3 randomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  return Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
}

// The oracle for distances: the triangle sampled on a fine barycentric grid.
double sampledDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  constexpr int kSteps = 200;
  double best = std::numeric_limits<double>::infinity();
  for (int i = 0; i <= kSteps; ++i) {
    for (int j = 0; i + j <= kSteps; ++j) {
      const double u = double(i) / kSteps, v = double(j) / kSteps;
      best = std::min(best, (a + u * (b - a) + v * (c - a) - p).norm());
    }
  }
  return best;
}

// The oracle for box overlap: the box's 12 triangles against the triangle, or a corner of
// the triangle inside the box.
bool boxTriangleOverlap(const OrientedBox& box, const Vec3& a, const Vec3& b, const Vec3& c) {
  const TriangleMesh cube = gen::makeBox(box.half);
  for (const Vec3& v : {a, b, c}) {
    const Vec3 local = box.axes.transpose() * (v - box.centre);
    if ((local.cwiseAbs().array() <= box.half.array()).all()) return true;
  }
  for (const Triangle& t : cube.triangles()) {
    const Vec3 p = box.axes * cube.vertices()[t[0]] + box.centre;
    const Vec3 q = box.axes * cube.vertices()[t[1]] + box.centre;
    const Vec3 r = box.axes * cube.vertices()[t[2]] + box.centre;
    if (trianglesIntersect(p, q, r, a, b, c)) return true;
  }
  return false;
}

TEST(PrimitiveContact, ClosestPointMatchesSamplingOnRandomAndDegenerateTriangles) {
  std::mt19937_64 rng(test::kSeed);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 a = randomPoint(rng, 1), b = randomPoint(rng, 1);
    Vec3 c = randomPoint(rng, 1);
    if (trial % 10 == 0) c = a + 0.3 * (b - a);  // collinear
    if (trial % 10 == 1) c = a;                  // two corners coincide
    const Vec3 p = randomPoint(rng, 2);
    const Vec3 q = closestPointOnTriangle(p, a, b, c);
    ASSERT_TRUE(q.allFinite());
    // The grid's spacing bounds the oracle's error: 1/200 of the triangle's size.
    const double tolerance = 0.02;
    EXPECT_NEAR((q - p).norm(), sampledDistance(p, a, b, c), tolerance) << "trial " << trial;
  }
}

TEST(PrimitiveContact, SphereSeparationIsTheDistanceMinusTheRadius) {
  std::mt19937_64 rng(test::kSeed + 1);
  for (int trial = 0; trial < 100; ++trial) {
    const Vec3 a = randomPoint(rng, 1), b = randomPoint(rng, 1), c = randomPoint(rng, 1);
    const Vec3 centre = randomPoint(rng, 1.5);
    const double radius = 0.3;
    PrimitiveContacts found;
    sphereTriangleContacts(centre, radius, a, b, c, 10.0, found);
    ASSERT_EQ(found.count, 1);
    const PrimitiveContact& p = found.points[0];
    EXPECT_NEAR(p.separation, sampledDistance(centre, a, b, c) - radius, 0.02);
    EXPECT_NEAR(p.normal.norm(), 1.0, 1e-12);
    // The sphere's nearest point is along the normal from the triangle's point.
    EXPECT_NEAR((centre - p.normal * (radius + p.separation) - p.onTriangle).norm(), 0.0, 1e-9);
  }
}

TEST(PrimitiveContact, SphereOutOfReachGivesNothing) {
  PrimitiveContacts found;
  sphereTriangleContacts(Vec3(0, 0, 2), 0.5, Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 1.0,
                         found);
  EXPECT_EQ(found.count, 0);  // 1.5 apart, reach 1
  sphereTriangleContacts(Vec3(0, 0, 2), 0.5, Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), 1.6,
                         found);
  ASSERT_EQ(found.count, 1);
  EXPECT_NEAR(found.points[0].separation, 1.5, 1e-12);
}

TEST(PrimitiveContact, CapsuleLyingOnAFaceRestsOnBothEnds) {
  // A big triangle in z = 0, a capsule of radius 0.1 along x, its axis 0.09 above: 0.01 deep.
  const Vec3 a(-5, -5, 0), b(5, -5, 0), c(0, 5, 0);
  PrimitiveContacts found;
  capsuleTriangleContacts(Vec3(-1, 0, 0.09), Vec3(1, 0, 0.09), 0.1, a, b, c, 0.05, found);
  ASSERT_EQ(found.count, 2);
  for (int i = 0; i < 2; ++i) {
    EXPECT_NEAR(found.points[i].separation, -0.01, 1e-12);
    EXPECT_NEAR(found.points[i].normal.z(), 1.0, 1e-12);
    EXPECT_NEAR(std::abs(found.points[i].onTriangle.x()), 1.0, 1e-12);
  }
}

TEST(PrimitiveContact, CapsuleThroughAFaceIsPushedOutTowardsItsLongerPart) {
  // The axis pierces z = 0 at the origin: 0.3 below, 1.0 above. Out along +z by 0.3 + r.
  const Vec3 a(-5, -5, 0), b(5, -5, 0), c(0, 5, 0);
  PrimitiveContacts found;
  capsuleTriangleContacts(Vec3(0, 0, -0.3), Vec3(0, 0, 1.0), 0.1, a, b, c, 0.05, found);
  ASSERT_GE(found.count, 1);
  const PrimitiveContact& deepest = found.points[found.count - 1];
  EXPECT_NEAR(deepest.separation, -0.4, 1e-12);
  EXPECT_NEAR(deepest.normal.z(), 1.0, 1e-12);
}

TEST(PrimitiveContact, CapsuleAgainstAnEdgeUsesTheAxisPoint) {
  // Triangle in z = 0, x >= 0. The axis runs from (-1, 0, 0.5) to (0.5, 0, -1), crossing
  // the plane outside the triangle: its closest point, (-0.25, 0, -0.25), faces the edge
  // point (0, 0, 0); both ends are out of reach.
  const Vec3 a(0, -1, 0), b(2, 0, 0), c(0, 1, 0);
  PrimitiveContacts found;
  capsuleTriangleContacts(Vec3(-1, 0, 0.5), Vec3(0.5, 0, -1), 0.4, a, b, c, 0.05, found);
  ASSERT_EQ(found.count, 1);
  EXPECT_NEAR(found.points[0].separation, std::sqrt(0.125) - 0.4, 1e-12);
  EXPECT_NEAR((found.points[0].normal - Vec3(-1, 0, -1).normalized()).norm(), 0.0, 1e-12);
  EXPECT_NEAR(found.points[0].onTriangle.norm(), 0.0, 1e-12);
}

TEST(PrimitiveContact, BoxFlatOnATriangleRestsOnFourCorners) {
  OrientedBox box;
  box.centre = Vec3(0, 0, 0.49);  // half height 0.5: 0.01 deep into z = 0
  box.half = Vec3(0.5, 0.3, 0.5);
  box.axes = Eigen::AngleAxisd(0.3, Vec3::UnitZ()).toRotationMatrix();
  PrimitiveContacts found;
  boxTriangleContacts(box, Vec3(-5, -5, 0), Vec3(5, -5, 0), Vec3(0, 5, 0), 0.02, found);
  ASSERT_EQ(found.count, 4);
  for (int i = 0; i < 4; ++i) {
    EXPECT_NEAR(found.points[i].separation, -0.01, 1e-12);
    EXPECT_NEAR(found.points[i].normal.z(), 1.0, 1e-12);
    EXPECT_NEAR(found.points[i].onTriangle.z(), 0.0, 1e-12);
  }
}

TEST(PrimitiveContact, SmallTriangleOnABoxFaceGivesItsCorners) {
  OrientedBox box;
  box.half = Vec3(1, 1, 1);
  PrimitiveContacts found;
  // A small triangle 0.02 into the top face, tilted a little.
  boxTriangleContacts(box, Vec3(0, 0, 0.98), Vec3(0.2, 0, 0.985), Vec3(0, 0.2, 0.99), 0.05,
                      found);
  ASSERT_EQ(found.count, 3);
  double deepest = 0.0;
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(found.points[i].normal.z(), -1.0, 1e-12);  // from the triangle to the box
    deepest = std::min(deepest, found.points[i].separation);
  }
  EXPECT_NEAR(deepest, -0.02, 1e-12);
}

// A floor 5 cm thick (a box, half height 0.025, top at z = 0.025) and a large flat triangle of
// a body pressed 3.5 cm into it from above, 70 % of the way through: the nearest face is the
// floor's underside, and the plain separating axis pushes the body on through it. With the
// way the body was pushed out last step (up), it is pushed back up, by its full depth.
TEST(PrimitiveContact, ABodyPressedPastHalfwayIntoAThinBoxIsPushedBackTheWayItCameIn) {
  OrientedBox floor;
  floor.half = Vec3(2, 2, 0.025);
  const Vec3 a(-1, -1, -0.01), b(1, -1, -0.01), c(0, 1, -0.01);
  PrimitiveContacts plain, hinted;
  boxTriangleContacts(floor, a, b, c, 0.01, plain);
  boxTriangleContacts(floor, a, b, c, 0.01, hinted, Vec3(0, 0, 3));  // any length
  ASSERT_GT(plain.count, 0);
  ASSERT_GT(hinted.count, 0);
  for (int i = 0; i < plain.count; ++i) {
    EXPECT_NEAR(plain.points[i].normal.z(), 1.0, 1e-12);  // triangle to box: pushed down
    EXPECT_NEAR(plain.points[i].separation, -0.015, 1e-12);
  }
  for (int i = 0; i < hinted.count; ++i) {
    EXPECT_NEAR(hinted.points[i].normal.z(), -1.0, 1e-12);  // pushed back up
    EXPECT_NEAR(hinted.points[i].separation, -0.035, 1e-12);
  }
  // Less than halfway in, the hint changes nothing.
  PrimitiveContacts shallow, shallowHinted;
  const Vec3 up(0, 0, 0.03);
  boxTriangleContacts(floor, a + up, b + up, c + up, 0.01, shallow);
  boxTriangleContacts(floor, a + up, b + up, c + up, 0.01, shallowHinted, Vec3(0, 0, 1));
  ASSERT_EQ(shallow.count, shallowHinted.count);
  for (int i = 0; i < shallow.count; ++i) {
    EXPECT_EQ(shallow.points[i].normal, shallowHinted.points[i].normal);
    EXPECT_EQ(shallow.points[i].separation, shallowHinted.points[i].separation);
  }
  // A triangle already through (below the underside) is not pulled back up through the
  // floor: it is apart, with or without the hint.
  PrimitiveContacts through;
  const Vec3 down(0, 0, -0.02);
  boxTriangleContacts(floor, a + down, b + down, c + down, 0.001, through, Vec3(0, 0, 1));
  EXPECT_EQ(through.count, 0);
}

TEST(PrimitiveContact, BoxSeparationAgreesWithTheExactOverlapTest) {
  std::mt19937_64 rng(test::kSeed + 2);
  int overlapping = 0, apart = 0;
  for (int trial = 0; trial < 400; ++trial) {
    OrientedBox box;
    box.centre = randomPoint(rng, 0.5);
    box.axes = randomRotation(rng);
    box.half = Vec3(0.2, 0.5, 0.35);
    const Vec3 a = randomPoint(rng, 1), b = randomPoint(rng, 1), c = randomPoint(rng, 1);
    PrimitiveContacts found;
    boxTriangleContacts(box, a, b, c, 100.0, found);
    ASSERT_GE(found.count, 1);
    // The deepest point carries the separating axis's separation (the others their own).
    int deepest = 0;
    for (int i = 1; i < found.count; ++i) {
      if (found.points[i].separation < found.points[deepest].separation) deepest = i;
    }
    const double separation = found.points[deepest].separation;
    const Vec3 normal = found.points[deepest].normal;
    if (std::abs(separation) < 1e-6) continue;  // touching: either answer is right
    const bool overlap = boxTriangleOverlap(box, a, b, c);
    EXPECT_EQ(overlap, separation < 0) << "trial " << trial << " separation " << separation;
    if (!overlap) {
      ++apart;
      continue;
    }
    ++overlapping;
    // Moving the triangle away along the normal by the depth (and a little) separates.
    const Vec3 away = -normal * (-separation + 1e-6);
    EXPECT_FALSE(boxTriangleOverlap(box, a + away, b + away, c + away)) << "trial " << trial;
  }
  EXPECT_GT(overlapping, 50);
  EXPECT_GT(apart, 50);
}

TEST(PrimitiveContact, NonFiniteInputGivesNoContactAndNoNaN) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Vec3 a(0, 0, 0), b(1, 0, 0), bad(nan, 0, 0);
  PrimitiveContacts found;
  OrientedBox box;
  box.half = Vec3(1, 1, 1);
  boxTriangleContacts(box, a, b, bad, 1.0, found);
  sphereTriangleContacts(bad, 1.0, a, b, Vec3(0, 1, 0), 1.0, found);
  capsuleTriangleContacts(a, bad, 1.0, a, b, Vec3(0, 1, 0), 1.0, found);
  for (int i = 0; i < found.count; ++i) {
    EXPECT_TRUE(found.points[i].onTriangle.allFinite());
    EXPECT_TRUE(found.points[i].normal.allFinite());
    EXPECT_TRUE(std::isfinite(found.points[i].separation));
  }
}

TEST(PrimitiveContact, OrientedBoxQueryFindsEveryTriangleTheBruteForceDoesAndFewerThanTheAabb) {
  const TriangleMesh mesh = gen::makeModel("knot", 4000);
  const AdbTree tree(mesh);
  std::mt19937_64 rng(test::kSeed + 3);
  std::size_t oriented = 0, aligned = 0;
  for (int trial = 0; trial < 30; ++trial) {
    OrientedBox box;
    box.centre = mesh.vertices()[rng() % mesh.vertices().size()];
    box.axes = randomRotation(rng);
    box.half = Vec3(0.8, 0.05, 0.8) * mesh.bounds().extent().norm() * 0.2;  // a tilted slab
    std::vector<bool> reported(mesh.triangleCount(), false);
    forEachTriangleNear(tree, box, [&](std::uint32_t t) {
      reported[tree.meshTriangle(t)] = true;
      ++oriented;
    });
    Aabb bounds;
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 s((corner & 1) ? 1 : -1, (corner & 2) ? 1 : -1, (corner & 4) ? 1 : -1);
      bounds.grow(box.centre + box.axes * s.cwiseProduct(box.half));
    }
    forEachTriangleNear(tree, bounds, [&](std::uint32_t) { ++aligned; });
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
      const Triangle& tri = mesh.triangles()[t];
      if (boxTriangleOverlap(box, mesh.vertices()[tri[0]], mesh.vertices()[tri[1]],
                             mesh.vertices()[tri[2]])) {
        EXPECT_TRUE(reported[t]) << "trial " << trial << " triangle " << t;
      }
    }
  }
  EXPECT_LT(oriented * 2, aligned);  // a tilted slab: its AABB holds far more
}

}  // namespace
}  // namespace adb

namespace adb {
namespace {

TEST(PrimitiveContact, CapsuleThroughAFaceNearItsEndPushesOneWayOnly) {
  // The short part (0.1 above the plane) is within the radius: its end contact would push
  // down while the through contact pushes up. Only the through contact remains.
  const Vec3 a(-10, -10, 0), b(10, -10, 0), c(0, 10, 0);
  for (const auto& [p0, p1] : {std::pair{Vec3(0, 0, 0.1), Vec3(0, 0, -0.9)},
                               std::pair{Vec3(-1, 0, 0.3), Vec3(1, 0, -0.3)}}) {
    PrimitiveContacts found;
    capsuleTriangleContacts(p0, p1, 0.5, a, b, c, 0.05, found);
    ASSERT_GE(found.count, 1);
    for (int i = 0; i < found.count; ++i) {
      EXPECT_GT(found.points[i].normal.dot(found.points[0].normal), 0.0) << "contact " << i;
    }
  }
}

TEST(PrimitiveContact, CapsuleCrossingBesideATriangleKeepsOneSide) {
  // The axis crosses z = 0 beside the triangle (x < 0); its ends are on both sides of the
  // plane, both within reach of the edge x = 0.
  const Vec3 a(0, -1, 0), b(2, 0, 0), c(0, 1, 0);
  PrimitiveContacts found;
  capsuleTriangleContacts(Vec3(-0.1, 0, 0.3), Vec3(-0.1, 0, -0.3), 0.35, a, b, c, 0.05, found);
  ASSERT_GE(found.count, 1);
  for (int i = 0; i < found.count; ++i) {
    for (int j = 0; j < i; ++j) {
      EXPECT_GT(found.points[i].normal.dot(found.points[j].normal), 0.0) << i << " " << j;
    }
  }
}

TEST(PrimitiveContact, NonFiniteOrNegativeSizesGiveNoContact) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Vec3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  for (const Vec3& half : {Vec3(inf, 1, 1), Vec3(nan, 1, 1), Vec3(-1, 1, 1)}) {
    OrientedBox box;
    box.half = half;
    PrimitiveContacts found;
    boxTriangleContacts(box, a, b, c, 1.0, found);
    EXPECT_EQ(found.count, 0);
  }
  for (const double r : {inf, nan, -1.0}) {
    PrimitiveContacts found;
    sphereTriangleContacts(Vec3(0, 0, 0.1), r, a, b, c, 1.0, found);
    capsuleTriangleContacts(Vec3(0, 0, 0.1), Vec3(0.1, 0, 0.1), r, a, b, c, 1.0, found);
    EXPECT_EQ(found.count, 0) << r;
  }
}

}  // namespace
}  // namespace adb
