// forEachTriangleNear: every triangle overlapping the box is reported (none missed), against
// brute force over all triangles, and each at most once.
#include <gtest/gtest.h>

#include <random>

#include "adb/core/box_query.h"
#include "adb/core/mesh_generators.h"
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

}  // namespace
}  // namespace adb
