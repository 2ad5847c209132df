// forEachTriangleNear: every triangle overlapping the box is reported (none missed), against
// brute force over all triangles, and each at most once. forEachDeepestTriangleNear: the
// deepest point is always found (brute force), with far fewer triangles on a resting face.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <vector>

#include "adb/core/box_query.h"
#include "adb/support/mesh_generators.h"
#include "test_support.h"

namespace adb {
namespace {

Aabb triangleBox(const TriangleMesh& m, std::size_t t) {
  Aabb b;
  for (std::uint32_t v : m.triangles()[t]) b.grow(m.vertices()[v]);
  return b;
}

bool overlaps(const Aabb& a, const Aabb& b) {
  return !((a.lo.array() > b.hi.array()).any() || (a.hi.array() < b.lo.array()).any());
}

TEST(BoxQuery, ReportsEveryOverlappingTriangleOnce) {
  const TriangleMesh mesh =
      gen::transformed(gen::makeModel("knot", 5000), Pose{Mat3::Identity(), Vec3(1e5, 3, -2)});
  const AdbTree tree(mesh);
  std::mt19937_64 rng(test::kSeed);
  std::uniform_real_distribution<double> u(-1.2, 1.2), size(0.0, 0.6);
  for (int q = 0; q < 200; ++q) {
    const Vec3 c = mesh.bounds().center() + Vec3(u(rng), u(rng), u(rng));
    const Vec3 h(size(rng), size(rng), q % 10 == 0 ? 0.0 : size(rng));  // some flat boxes
    const Aabb box{c - h, c + h};
    std::vector<int> seen(mesh.triangleCount(), 0);
    forEachTriangleNear(tree, box, [&](std::uint32_t t) { ++seen[tree.meshTriangle(t)]; });
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
      ASSERT_LE(seen[t], 1);
      if (overlaps(triangleBox(mesh, t), box)) {
        ASSERT_EQ(seen[t], 1) << "query " << q;
      }
    }
  }
}

TEST(BoxQuery, EmptyAndDistantBoxesReportNothing) {
  const TriangleMesh mesh = gen::makeSphere(1.0, 3);
  const AdbTree tree(mesh);
  int calls = 0;
  forEachTriangleNear(tree, Aabb{}, [&](std::uint32_t) { ++calls; });
  forEachTriangleNear(tree, Aabb{Vec3(5, 5, 5), Vec3(6, 6, 6)}, [&](std::uint32_t) { ++calls; });
  EXPECT_EQ(calls, 0);
}

// How deep a tree-local point lies inside the box (negative outside).
double pointDepth(const Vec3& p, const OrientedBox& box) {
  const Vec3 q = box.axes.transpose() * (p - box.centre);
  return (box.half - q.cwiseAbs()).minCoeff();
}

// The depth the test's contact function gives a tree triangle: its deepest vertex's.
double triangleDepth(const AdbTree& tree, std::uint32_t t, const OrientedBox& box) {
  double d = -std::numeric_limits<double>::infinity();
  for (std::uint32_t v : tree.triangles()[t]) {
    d = std::max(d, pointDepth(tree.localVertices()[v], box));
  }
  return d;
}

OrientedBox randomBox(std::mt19937_64& rng, const Vec3& around) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), size(0.05, 0.8);
  OrientedBox b;
  b.centre = around + Vec3(u(rng), u(rng), u(rng));
  b.axes = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
  b.half = Vec3(size(rng), size(rng), size(rng));
  return b;
}

TEST(DeepestTriangleQuery, FindsTheDeepestPointAgainstBruteForce) {
  const TriangleMesh mesh =
      gen::transformed(gen::makeModel("knot", 5000), Pose{Mat3::Identity(), Vec3(1e4, 3, -2)});
  const AdbTree tree(mesh);
  std::mt19937_64 rng(test::kSeed);
  constexpr double kSlack = 1e-3;
  int deepQueries = 0;
  for (int q = 0; q < 300; ++q) {
    OrientedBox solid = randomBox(rng, Vec3::Zero());  // tree-local
    const double reach = q % 2 == 0 ? 0.0 : 0.05;
    double brute = -std::numeric_limits<double>::infinity();
    for (std::uint32_t t = 0; t < tree.triangles().size(); ++t) {
      brute = std::max(brute, triangleDepth(tree, t, solid));
    }
    for (int level : {0, 3, 30}) {
      double found = -std::numeric_limits<double>::infinity();
      std::vector<int> seen(tree.triangles().size(), 0);
      forEachDeepestTriangleNear(tree, solid, reach, level, kSlack, [&](std::uint32_t t) {
        ++seen[t];
        const double d = triangleDepth(tree, t, solid);
        found = std::max(found, d);
        return d;
      });
      for (int n : seen) ASSERT_LE(n, 1) << "query " << q;
      if (brute > -reach) {  // within reach: the deepest is found, within the slack
        ASSERT_GE(found, brute - kSlack) << "query " << q << " level " << level;
      }
    }
    deepQueries += brute > 0.0 ? 1 : 0;
  }
  EXPECT_GT(deepQueries, 30);  // the boxes do reach into the knot
}

TEST(DeepestTriangleQuery, AFaceRestingOnABoxTakesAFractionOfTheTriangles) {
  // A flat grid of 20k triangles sunk 0.01 into a floor box: every triangle within reach
  // is as deep as any other; each of the 16 regions needs only its first leaf.
  const TriangleMesh grid = gen::makeFlatGrid(2.0, 2.0, 100, 100);
  const AdbTree tree(grid);
  OrientedBox floor;
  floor.half = Vec3(5, 5, 1);
  floor.centre = -tree.origin() - Vec3::UnitZ() * (floor.half.z() - 0.01);  // top at z = 0.01
  OrientedBox cull{floor.centre + tree.origin(), floor.axes, floor.half + Vec3::Constant(0.02)};
  std::size_t all = 0, sampled = 0;
  double deepest = -1.0;
  forEachTriangleNear(tree, cull, [&](std::uint32_t) { ++all; });
  forEachDeepestTriangleNear(tree, floor, 0.02, 4, 1e-3, [&](std::uint32_t t) {
    ++sampled;
    const double d = triangleDepth(tree, t, floor);
    deepest = std::max(deepest, d);
    return d;
  });
  EXPECT_EQ(all, grid.triangleCount());
  EXPECT_NEAR(deepest, 0.01, 1e-6);
  EXPECT_LE(sampled, 16u * 16u) << "of " << all;
}

}  // namespace
}  // namespace adb
