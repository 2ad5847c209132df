// The penetration probe (adb/scene/penetration_probe.h) against closed forms: it is
// the measure the budget's plausibility is judged by, so it must be right.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "adb/support/mesh_generators.h"
#include "adb/scene/penetration_probe.h"

namespace adb::scene {
namespace {

constexpr double kMajor = 0.35, kMinor = 0.12;
constexpr double kPi = 3.14159265358979323846;

// Distance from the tube's centre circle of a torus around z (mesh coordinates).
double tubeDistance(const Vec3& p) { return std::hypot(std::hypot(p.x(), p.y()) - kMajor, p.z()); }

struct Torus {
  TriangleMesh mesh = gen::makeTorus(kMajor, kMinor, 48, 24);
  AdbTree tree{mesh};
  std::vector<Vec3> vertices = mesh.vertices();
};

TEST(PenetrationProbe, InsideAndDepthMatchATorusClosedForm) {
  const Torus t;
  // The tessellated tube lies within kMinor (1 - cos(pi / 24)) of the true one (and the ring
  // within kMajor (1 - cos(pi / 48))): points farther than that from the surface are decided
  // exactly, and depths agree within it.
  const double tessellation = kMinor * (1 - std::cos(kPi / 24)) + kMajor * (1 - std::cos(kPi / 48));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  int inside = 0;
  for (int i = 0; i < 4000; ++i) {
    const Vec3 p(u(rng), u(rng), 0.3 * u(rng));
    const double r = tubeDistance(p);
    if (std::abs(r - kMinor) < 2 * tessellation) continue;  // too near the surface to judge
    const Vec3 local = p - t.tree.origin();
    ASSERT_EQ(insideMesh(t.tree, local), r < kMinor) << p.transpose();
    if (r < kMinor) {
      ++inside;
      EXPECT_NEAR(distanceToMesh(t.tree, local), kMinor - r, 2 * tessellation) << p.transpose();
    }
  }
  EXPECT_GT(inside, 100);
}

TEST(PenetrationProbe, TwoToriPushedTogetherAreAsDeepAsTheirOverlap) {
  const Torus t;
  // Two tori side by side in their plane, tubes overlapping by `overlap` along x: the vertex
  // of one on its outer equator, on the line between the centres, lies `overlap` inside the
  // other's tube (two circles overlapping by d: each one's extreme point is d deep in the
  // other), and is the deepest; touching, nothing is inside.
  for (double overlap : {0.0, 0.02, 0.05, 0.1}) {
    const double gap = 2 * (kMajor + kMinor) - overlap;
    const std::vector<ProbeBody> bodies = {
        {&t.tree, &t.vertices, Pose{}},
        {&t.tree, &t.vertices, Pose{Mat3::Identity(), Vec3(gap, 0, 0)}}};
    const PenetrationReport r = measurePenetration(bodies);
    EXPECT_EQ(r.pairsTested, 1u);
    EXPECT_NEAR(r.depth, overlap, 0.005) << "overlap " << overlap;
    EXPECT_NEAR(r.relative, r.depth / (2 * Vec3(kMajor + kMinor, kMajor + kMinor, kMinor).norm()),
                1e-3);
  }
  // Far apart: their boxes do not even overlap.
  const std::vector<ProbeBody> apart = {{&t.tree, &t.vertices, Pose{}},
                                        {&t.tree, &t.vertices, Pose{Mat3::Identity(), Vec3(5, 0, 0)}}};
  EXPECT_EQ(measurePenetration(apart).pairsTested, 0u);
}

}  // namespace
}  // namespace adb::scene
