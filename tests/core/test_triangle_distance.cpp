// triangleDistance against known answers and an optimality certificate (the plane through the
// closest points, perpendicular to their difference, separates the triangles); the exact
// query's contact margin against brute force over every triangle pair.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "adb/core/primitive_contact.h"
#include "adb/core/query.h"
#include "adb/core/tree.h"
#include "adb/core/triangle_distance.h"
#include "adb/core/triangle_test.h"
#include "adb/support/benchmark_poses.h"
#include "adb/support/mesh_generators.h"
#include "test_support.h"

namespace adb {
namespace {

// Whether p lies in triangle (a, b, c) within `tol` (its distance to the closest point).
double distanceToTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  return (closestPointOnTriangle(p, a, b, c) - p).norm();
}

TEST(TriangleDistance, ParallelFacesApartAlongTheirNormal) {
  const Vec3 a0(0, 0, 0), a1(1, 0, 0), a2(0, 1, 0);
  const Vec3 b0(0.1, 0.1, 0.25), b1(0.5, 0.1, 0.25), b2(0.1, 0.5, 0.25);
  const TriangleDistance d = triangleDistance(a0, a1, a2, b0, b1, b2);
  EXPECT_NEAR(d.distance, 0.25, 1e-15);
  EXPECT_NEAR((d.pointOnB - d.pointOnA).normalized().z(), 1.0, 1e-12);
}

TEST(TriangleDistance, CrossedEdgesMeetAtTheirCommonPerpendicular) {
  // A's edge along x at z = 0, B's edge along y at z = 0.3: the closest points are (0.5, 0, 0)
  // and (0.5, 0, 0.3), in the middle of both edges (not at any vertex).
  const Vec3 a0(0, 0, 0), a1(1, 0, 0), a2(0.5, 0, -1);
  const Vec3 b0(0.5, -0.5, 0.3), b1(0.5, 0.5, 0.3), b2(0.5, 0, 1.3);
  const TriangleDistance d = triangleDistance(a0, a1, a2, b0, b1, b2);
  EXPECT_NEAR(d.distance, 0.3, 1e-15);
  EXPECT_NEAR((d.pointOnA - Vec3(0.5, 0, 0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((d.pointOnB - Vec3(0.5, 0, 0.3)).norm(), 0.0, 1e-15);
}

TEST(TriangleDistance, DegenerateTrianglesAreTheirEdgesAndPoints) {
  const Vec3 p(0.2, 0.2, 2.0);  // a triangle collapsed to a point above A
  const TriangleDistance d =
      triangleDistance(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), p, p, p);
  EXPECT_NEAR(d.distance, 2.0, 1e-15);
  const TriangleDistance segment = triangleDistance(  // collinear corners: a segment
      Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(0.5, 1, 0), Vec3(0.5, 2, 0),
      Vec3(0.5, 3, 0));
  EXPECT_NEAR(segment.distance, 1.0, 1e-15);
}

TEST(TriangleDistance, NonFiniteInputGivesInfinityNotNaN) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const TriangleDistance d = triangleDistance(Vec3(nan, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0),
                                              Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1));
  EXPECT_TRUE(std::isinf(d.distance));
  EXPECT_TRUE(d.pointOnA.allFinite());
  EXPECT_TRUE(d.pointOnB.allFinite());
}

// The certificate: for separated convex sets, closest points pA, pB are optimal iff every
// point of A lies on A's side of the plane through pA perpendicular to n = pB - pA, and every
// point of B beyond the parallel plane through pB. Checked on the vertices (the triangles are
// their hulls), with both points on their triangles.
TEST(TriangleDistance, RandomSeparatedPairsAreCertifiedOptimal) {
  std::mt19937_64 rng(test::kSeed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto point = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  int checked = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const double scale = std::pow(10.0, std::uniform_int_distribution<int>(-4, 4)(rng));
    const Vec3 offset = point() * 1.5;
    const Vec3 a[3] = {point() * scale, point() * scale, point() * scale};
    const Vec3 b[3] = {(point() + offset) * scale, (point() + offset) * scale,
                       (point() + offset) * scale};
    if (trianglesIntersect(a[0], a[1], a[2], b[0], b[1], b[2])) continue;
    const TriangleDistance d = triangleDistance(a[0], a[1], a[2], b[0], b[1], b[2]);
    ASSERT_TRUE(std::isfinite(d.distance));
    const double tol = 1e-9 * scale;
    ASSERT_LE(distanceToTriangle(d.pointOnA, a[0], a[1], a[2]), tol);
    ASSERT_LE(distanceToTriangle(d.pointOnB, b[0], b[1], b[2]), tol);
    ASSERT_NEAR((d.pointOnB - d.pointOnA).norm(), d.distance, tol);
    ASSERT_GT(d.distance, 0.0);
    const Vec3 n = (d.pointOnB - d.pointOnA) / d.distance;
    for (const Vec3& v : a) ASSERT_LE(n.dot(v - d.pointOnA), tol) << "trial " << trial;
    for (const Vec3& v : b) ASSERT_GE(n.dot(v - d.pointOnB), -tol) << "trial " << trial;
    ++checked;
  }
  EXPECT_GT(checked, 10000);  // most random pairs at these offsets are apart
}

// f(i, j, distance) for every triangle pair of two posed copies of `tree` (distance 0 when
// they cross), by brute force.
template <class F>
void forEveryTrianglePair(const AdbTree& tree, const Pose& pa, const Pose& pb, F&& f) {
  const auto& v = tree.localVertices();
  const auto& t = tree.triangles();
  const auto world = [&](const Pose& p, std::uint32_t tri, int k) {
    return p.apply(v[t[tri][k]] + tree.origin());
  };
  for (std::uint32_t i = 0; i < t.size(); ++i) {
    for (std::uint32_t j = 0; j < t.size(); ++j) {
      const Vec3 a[3] = {world(pa, i, 0), world(pa, i, 1), world(pa, i, 2)};
      const Vec3 b[3] = {world(pb, j, 0), world(pb, j, 1), world(pb, j, 2)};
      f(i, j, trianglesIntersect(a[0], a[1], a[2], b[0], b[1], b[2])
                  ? 0.0
                  : triangleDistance(a[0], a[1], a[2], b[0], b[1], b[2]).distance);
    }
  }
}

// Every triangle pair within `margin` of each other (crossing or not), by brute force.
std::set<std::pair<std::uint32_t, std::uint32_t>> pairsWithin(const AdbTree& tree,
                                                              const Pose& pa, const Pose& pb,
                                                              double margin) {
  std::set<std::pair<std::uint32_t, std::uint32_t>> out;
  forEveryTrianglePair(tree, pa, pb, [&](std::uint32_t i, std::uint32_t j, double distance) {
    if (distance <= margin) out.insert({i, j});
  });
  return out;
}

TEST(ContactMargin, FindsExactlyThePairsWithinTheMargin) {
  const TriangleMesh mesh = gen::makeTorus(1.0, 0.35, 16, 8);
  AdbTree tree(mesh);
  QueryScratch scratch;
  QuerySettings s = test::collectEverySettings();
  s.contactMargin = 0.05;
  std::mt19937_64 rng(test::kSeed);
  int near = 0, withNearOnly = 0;
  // Random poses at four distances, and side by side 0.03 apart: within the margin only.
  std::vector<PosePair> poses;
  for (double dist : {0.5, 1.2, 1.9, 2.05}) {
    for (int i = 0; i < 3; ++i) poses.push_back(benchmarkPoses(mesh.bounds(), dist, rng));
  }
  const double across = mesh.bounds().hi.x() - mesh.bounds().lo.x();
  poses.push_back({Pose{}, Pose{Mat3::Identity(), Vec3(across + 0.03, 0, 0)}});
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const PosePair& p = poses[i];
    const QueryResult r = collide(tree, p.a, tree, p.b, s, scratch);
    const auto expected = pairsWithin(tree, p.a, p.b, s.contactMargin);
    std::set<std::pair<std::uint32_t, std::uint32_t>> found;
    bool crossing = false;
    for (const Witness& w : scratch.witnesses()) {
      found.insert({w.triangleA, w.triangleB});
      near += w.distance > 0.0f ? 1 : 0;
      crossing = crossing || w.distance == 0.0f;
      EXPECT_LE(w.distance, s.contactMargin * (1 + 1e-6));
    }
    EXPECT_EQ(found, expected) << "pose " << i;
    EXPECT_EQ(r.collides, !expected.empty());
    withNearOnly += (!expected.empty() && !crossing) ? 1 : 0;
  }
  EXPECT_GT(near, 0);          // the margin made contacts the plain test would not
  EXPECT_GT(withNearOnly, 0);  // and some poses are "within the margin" only
}

// Every triangle pair's distance (0 when they cross), by brute force, sorted.
std::vector<double> pairDistances(const AdbTree& tree, const Pose& pa, const Pose& pb) {
  std::vector<double> out;
  forEveryTrianglePair(tree, pa, pb, [&](std::uint32_t, std::uint32_t, double distance) {
    out.push_back(distance);
  });
  std::sort(out.begin(), out.end());
  return out;
}

TEST(ContactMargin, AFullWitnessListKeepsTheClosestPairsAndPrunesTheRest) {
  // Two gears face to face 0.02 apart under a margin of 0.3: thousands of triangle pairs
  // within the margin, 16 witness slots. The list keeps the 16 closest (brute force), and
  // once full the margin shrinks to its farthest witness, so the query evaluates fewer node
  // pairs than it needs to keep every pair within the margin (measured: 2.9x fewer at 0.02
  // apart, 1.9x at 0.1; the descent is in tree order, so the first witnesses are not the
  // closest).
  const TriangleMesh mesh = gen::makeGear(12, 1.0, 0.8, 0.3, 0.3, 4);
  AdbTree tree(mesh);
  QueryScratch scratch;
  const double thickness = mesh.bounds().hi.z() - mesh.bounds().lo.z();
  for (double gap : {0.02, 0.1}) {
    SCOPED_TRACE(gap);
    const Pose a{}, b{Mat3::Identity(), Vec3(0.05, 0.03, thickness + gap)};
    QuerySettings s = test::collectEverySettings();
    s.contactMargin = 0.3;
    const QueryResult all = collide(tree, a, tree, b, s, scratch);
    s.maxWitnesses = 16;
    const QueryResult closest = collide(tree, a, tree, b, s, scratch);
    const std::vector<double> expected = pairDistances(tree, a, b);
    ASSERT_GT(expected.size(), 16u);
    ASSERT_LE(expected[15], s.contactMargin);
    std::vector<double> found;
    for (const Witness& w : scratch.witnesses()) found.push_back(w.distance);
    std::sort(found.begin(), found.end());
    ASSERT_EQ(found.size(), 16u);
    for (std::size_t k = 0; k < 16; ++k) {
      // Witness distances are floats rounded up from the double distance.
      EXPECT_NEAR(found[k], expected[k], 1e-6 * (1.0 + expected[k])) << "rank " << k;
    }
    EXPECT_LT(closest.nodePairs * 3, all.nodePairs * 2)
        << "the full list's farthest witness must prune the node pairs beyond it";
  }
}

TEST(ContactMargin, ZeroMarginIsThePlainIntersectionQuery) {
  const TriangleMesh mesh = gen::makeGear(12, 1.0, 0.8, 0.3, 0.3, 4);
  AdbTree tree(mesh);
  QueryScratch scratch;
  QuerySettings s = test::collectEverySettings();
  std::mt19937_64 rng(test::kSeed);
  for (int i = 0; i < 6; ++i) {
    const PosePair p = benchmarkPoses(mesh.bounds(), 0.6 + 0.3 * i, rng);
    collide(tree, p.a, tree, p.b, s, scratch);
    std::size_t found = 0;
    for (const Witness& w : scratch.witnesses()) {
      EXPECT_EQ(w.distance, 0.0f);
      ++found;
    }
    EXPECT_EQ(found, pairsWithin(tree, p.a, p.b, 0.0).size());
  }
}

TEST(ContactMargin, NegativeOrNonFiniteMarginIsRefusedByName) {
  const TriangleMesh mesh = gen::makeTorus(1.0, 0.35, 8, 6);
  AdbTree tree(mesh);
  QueryScratch scratch;
  for (double bad : {-0.1, std::numeric_limits<double>::infinity(),
                     std::numeric_limits<double>::quiet_NaN()}) {
    QuerySettings s = test::exactSettings();
    s.contactMargin = bad;
    try {
      collide(tree, Pose{}, tree, Pose{}, s, scratch);
      ADD_FAILURE() << "accepted contactMargin " << bad;
    } catch (const SettingsError& e) {
      EXPECT_NE(std::string(e.what()).find("contactMargin"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace adb
