// forEachTriangleAlongSegment: against brute force over all triangles. With no pruning every
// triangle whose box the segment (or swept box) meets is reported, once; with the callback
// returning the closest hit, the closest hit equals the brute-force one. Rays parallel to
// axes, starting inside boxes, of zero length, far from the origin; refused input (NaN,
// infinity, inverted boxes) visits nothing.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "adb/support/mesh_generators.h"
#include "adb/core/ray_query.h"
#include "test_support.h"

namespace adb {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Triangle boxes are shrunk by this before the brute-force slab test: the tree's float boxes
// are rounded outward, so a segment grazing a box within rounding may go either way.
constexpr double kGraze = 1e-9;

Aabb triangleBox(const TriangleMesh& m, std::size_t t) {
  Aabb b;
  for (std::uint32_t v : m.triangles()[t]) b.grow(m.vertices()[v]);
  return b;
}

// Does the segment from + s (to - from), s in [0, 1], meet the box? Plain slab test in double.
bool segmentMeetsBox(const Vec3& from, const Vec3& to, const Aabb& box) {
  double t0 = 0.0, t1 = 1.0;
  for (int i = 0; i < 3; ++i) {
    const double d = to[i] - from[i];
    if (d == 0.0) {
      if (from[i] < box.lo[i] || from[i] > box.hi[i]) return false;
      continue;
    }
    double a = (box.lo[i] - from[i]) / d, b = (box.hi[i] - from[i]) / d;
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

// Moller-Trumbore: the fraction at which the segment crosses the triangle, or +inf.
double hitFraction(const TriangleMesh& m, std::size_t t, const Vec3& from, const Vec3& to) {
  const Triangle& tri = m.triangles()[t];
  const Vec3 &a = m.vertices()[tri[0]], &b = m.vertices()[tri[1]], &c = m.vertices()[tri[2]];
  const Vec3 d = to - from, e1 = b - a, e2 = c - a;
  const Vec3 p = d.cross(e2);
  const double det = e1.dot(p);
  if (det == 0.0) return kInf;
  const Vec3 s = from - a;
  const double u = s.dot(p) / det;
  if (u < 0.0 || u > 1.0) return kInf;
  const Vec3 q = s.cross(e1);
  const double v = d.dot(q) / det;
  if (v < 0.0 || u + v > 1.0) return kInf;
  const double f = e2.dot(q) / det;
  return f >= 0.0 && f <= 1.0 ? f : kInf;
}

struct Fixture {
  TriangleMesh mesh;
  AdbTree tree;
  explicit Fixture(TriangleMesh m) : mesh(std::move(m)), tree(mesh) {}
};

// Every triangle of the brute force reported, each once, with the callback never pruning.
void expectAllReported(const Fixture& f, const SegmentQuery& q, const char* what, int i) {
  std::vector<int> seen(f.mesh.triangleCount(), 0);
  const SegmentQueryStats stats = forEachTriangleAlongSegment(f.tree, q, 1.0, [&](std::uint32_t t) {
    ++seen[f.tree.meshTriangle(t)];
    return 1.0;
  });
  ASSERT_TRUE(stats.valid);
  for (std::size_t t = 0; t < f.mesh.triangleCount(); ++t) {
    ASSERT_LE(seen[t], 1) << what << " " << i;
    Aabb box = triangleBox(f.mesh, t);
    // The mover [p + sweptLo, p + sweptHi] meets the box when p is in this grown box.
    box.lo -= q.sweptHi + Vec3::Constant(q.pad - kGraze);
    box.hi -= q.sweptLo - Vec3::Constant(q.pad - kGraze);
    if (segmentMeetsBox(q.from, q.to, box)) {
      ASSERT_EQ(seen[t], 1) << what << " " << i << " triangle " << t;
    }
  }
}

// The closest hit through the pruned traversal equals the brute-force closest hit.
void expectClosestHit(const Fixture& f, const Vec3& from, const Vec3& to, int i,
                      std::uint32_t* visited = nullptr) {
  double brute = kInf;
  for (std::size_t t = 0; t < f.mesh.triangleCount(); ++t) {
    brute = std::min(brute, hitFraction(f.mesh, t, from, to));
  }
  double best = kInf;
  SegmentQuery q;
  q.from = from;
  q.to = to;
  const SegmentQueryStats stats = forEachTriangleAlongSegment(f.tree, q, 1.0, [&](std::uint32_t t) {
    best = std::min(best, hitFraction(f.mesh, f.tree.meshTriangle(t), from, to));
    return std::min(best, 1.0);
  });
  ASSERT_TRUE(stats.valid);
  ASSERT_EQ(best, brute) << "ray " << i;
  if (visited) *visited = stats.triangles;
}

TEST(RayQuery, RandomRaysReportEveryTriangleTheyMeetAndTheClosestHit) {
  const Fixture f(gen::makeModel("knot", 4000));
  std::mt19937_64 rng(test::kSeed);
  std::uniform_real_distribution<double> u(-1.5, 1.5);
  const Vec3 c = f.mesh.bounds().center();
  for (int i = 0; i < 150; ++i) {
    SegmentQuery q;
    q.from = c + Vec3(u(rng), u(rng), u(rng));
    q.to = c + Vec3(u(rng), u(rng), u(rng));
    expectAllReported(f, q, "ray", i);
    expectClosestHit(f, q.from, q.to, i);
  }
}

TEST(RayQuery, ClosestHitPrunesMostOfTheMesh) {
  const Fixture f(gen::makeModel("knot", 20000));
  std::mt19937_64 rng(test::kSeed + 1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Aabb b = f.mesh.bounds();
  std::uint64_t visited = 0;
  int hits = 0;
  for (int i = 0; i < 100; ++i) {
    // Through the mesh's box from well outside it: most rays hit.
    const Vec3 dir = Vec3(u(rng), u(rng), u(rng)).normalized();
    const Vec3 target = b.center() + 0.3 * b.extent().cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
    const Vec3 from = target - 2.0 * b.extent().norm() * dir;
    const Vec3 to = target + 2.0 * b.extent().norm() * dir;
    std::uint32_t n = 0;
    expectClosestHit(f, from, to, i, &n);
    visited += n;
    for (std::size_t t = 0; t < f.mesh.triangleCount(); ++t) {
      if (std::isfinite(hitFraction(f.mesh, t, from, to))) {
        ++hits;
        break;
      }
    }
  }
  EXPECT_GT(hits, 50);
  // Measured about 60 triangles per ray on this 20k mesh; a full box walk takes thousands.
  EXPECT_LT(visited / 100, 400u);
}

TEST(RayQuery, AxisParallelRaysAndRaysStartingInsideBoxes) {
  const Fixture f(gen::makeModel("gears", 3000));
  std::mt19937_64 rng(test::kSeed + 2);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Aabb b = f.mesh.bounds();
  for (int i = 0; i < 120; ++i) {
    // Starts inside the mesh's box (so inside the root and many inner boxes).
    const Vec3 from = b.center() + 0.5 * b.extent().cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
    Vec3 d = Vec3::Zero();
    const int axis = i % 3;
    d[axis] = (i % 2 ? 1.0 : -1.0) * b.extent().maxCoeff();
    if (i % 4 == 3) d[(axis + 1) % 3] = 0.5 * b.extent().maxCoeff();  // parallel to a plane
    SegmentQuery q;
    q.from = from;
    q.to = from + d;
    expectAllReported(f, q, "parallel ray", i);
    expectClosestHit(f, q.from, q.to, i);
  }
}

TEST(RayQuery, ZeroLengthSegmentReportsTheLeavesHoldingThePoint) {
  const Fixture f(gen::makeSphere(1.0, 12));
  std::mt19937_64 rng(test::kSeed + 3);
  std::uniform_real_distribution<double> u(-1.1, 1.1);
  for (int i = 0; i < 60; ++i) {
    SegmentQuery q;
    q.from = q.to = Vec3(u(rng), u(rng), u(rng));
    if (i % 3 == 0) q.from = q.to = f.mesh.vertices()[static_cast<std::size_t>(i)];  // on it
    expectAllReported(f, q, "point", i);
    expectClosestHit(f, q.from, q.to, i);  // no crossing: nothing hit, nothing NaN
  }
}

TEST(RayQuery, FarFromTheOrigin) {
  const Fixture f(gen::transformed(gen::makeModel("torus", 3000),
                                   Pose{Mat3::Identity(), Vec3(1e5, -3e4, 2)}));
  std::mt19937_64 rng(test::kSeed + 4);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  const Vec3 c = f.mesh.bounds().center();
  for (int i = 0; i < 80; ++i) {
    SegmentQuery q;
    q.from = c + Vec3(u(rng), u(rng), u(rng));
    q.to = c + Vec3(u(rng), u(rng), u(rng));
    expectAllReported(f, q, "far ray", i);
    expectClosestHit(f, q.from, q.to, i);
  }
}

TEST(RayQuery, SweptBoxesReportEveryTriangleTheirPathMeets) {
  const Fixture f(gen::makeModel("pipes", 4000));
  std::mt19937_64 rng(test::kSeed + 5);
  std::uniform_real_distribution<double> u(-1.2, 1.2), size(0.0, 0.2);
  const Vec3 c = f.mesh.bounds().center();
  for (int i = 0; i < 100; ++i) {
    SegmentQuery q;
    q.from = c + Vec3(u(rng), u(rng), u(rng));
    q.to = i % 5 == 0 ? q.from : c + Vec3(u(rng), u(rng), u(rng));
    // Off-centre boxes (a convex whose box is not centred on its origin) and pads.
    q.sweptLo = -Vec3(size(rng), size(rng), size(rng));
    q.sweptHi = Vec3(size(rng), size(rng), i % 7 == 0 ? 0.0 : size(rng));
    q.pad = i % 2 ? 0.01 : 0.0;
    q.relativePad = i % 3 ? 2e-4 : 0.0;
    expectAllReported(f, q, "swept box", i);
  }
}

TEST(RayQuery, RefusedInputVisitsNothing) {
  const Fixture f(gen::makeSphere(1.0, 4));
  int calls = 0;
  const auto count = [&](std::uint32_t) {
    ++calls;
    return 1.0;
  };
  const auto refused = [&](SegmentQuery q, double maxFraction = 1.0) {
    return !forEachTriangleAlongSegment(f.tree, q, maxFraction, count).valid;
  };
  SegmentQuery good;
  good.from = Vec3(-2, 0.1, 0.2);
  good.to = Vec3(2, 0.1, 0.2);
  SegmentQuery q = good;
  q.from.x() = kNaN;
  EXPECT_TRUE(refused(q));
  q = good;
  q.to.y() = kInf;
  EXPECT_TRUE(refused(q));
  q = good;
  q.sweptLo = Vec3(0.1, 0, 0);  // lo > hi
  EXPECT_TRUE(refused(q));
  q = good;
  q.pad = -1.0;
  EXPECT_TRUE(refused(q));
  q = good;
  q.relativePad = kNaN;
  EXPECT_TRUE(refused(q));
  q = good;
  q.from = Vec3(-1e308, 0, 0);
  q.to = Vec3(1e308, 0, 0);  // the direction overflows
  EXPECT_TRUE(refused(q));
  EXPECT_TRUE(refused(good, kNaN));
  EXPECT_EQ(calls, 0);
  // A negative bound is valid and visits nothing; a callback returning NaN prunes nothing.
  EXPECT_TRUE(forEachTriangleAlongSegment(f.tree, good, -1.0, count).valid);
  EXPECT_EQ(calls, 0);
  int nanCalls = 0;
  forEachTriangleAlongSegment(f.tree, good, 1.0, [&](std::uint32_t) {
    ++nanCalls;
    return kNaN;
  });
  const auto all = forEachTriangleAlongSegment(f.tree, good, 1.0, count).triangles;
  EXPECT_EQ(nanCalls, static_cast<int>(all));
  // Subnormal direction components are treated as parallel: no NaN, the right triangles.
  q = good;
  q.to = q.from + Vec3(4, 1e-310, -1e-320);
  expectAllReported(f, q, "subnormal", 0);
}

}  // namespace
}  // namespace adb
