// MeshShape: bounds under transforms and scaling, the triangles it reports to Bullet, mass
// properties, sharing one tree between shapes, bad scaling.
#include <gtest/gtest.h>

#include <random>

#include "adb/bullet/mesh_shape.h"
#include "adb/support/benchmark_poses.h"
#include "adb/support/mesh_generators.h"

namespace adb {
namespace {

constexpr std::uint64_t kSeed = 20261121;
// Bullet may be single precision: positions of size ~1 carry ~1e-7 relative rounding.
const double kBtTolerance = sizeof(btScalar) == sizeof(float) ? 1e-5 : 1e-12;

btTransform randomTransform(std::mt19937_64& rng) {
  const Eigen::Quaterniond q = randomRotation(rng);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  return btTransform(btQuaternion(static_cast<btScalar>(q.x()), static_cast<btScalar>(q.y()),
                                  static_cast<btScalar>(q.z()), static_cast<btScalar>(q.w())),
                     btVector3(static_cast<btScalar>(u(rng)), static_cast<btScalar>(u(rng)),
                               static_cast<btScalar>(u(rng))));
}

TEST(MeshShape, IsACustomConcaveShapeSharingItsTree) {
  const auto data = MeshData::build(gen::makeModel("knot", 2000));
  MeshShape a(data), b(data);
  EXPECT_EQ(a.getShapeType(), CUSTOM_CONCAVE_SHAPE_TYPE);
  EXPECT_TRUE(a.isConcave());
  EXPECT_EQ(&a.tree(), &b.tree());
}

TEST(MeshShape, AabbContainsEveryVertexUnderAnyTransform) {
  const auto data = MeshData::build(gen::makeModel("gears", 2000));
  MeshShape shape(data);
  std::mt19937_64 rng(kSeed);
  for (int i = 0; i < 50; ++i) {
    const btTransform t = randomTransform(rng);
    btVector3 lo, hi;
    shape.getAabb(t, lo, hi);
    for (const Vec3& v : data->mesh.vertices()) {
      const btVector3 w = t(btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
                                      static_cast<btScalar>(v.z())));
      for (int k = 0; k < 3; ++k) {
        ASSERT_GE(w[k], lo[k] - kBtTolerance);
        ASSERT_LE(w[k], hi[k] + kBtTolerance);
      }
    }
  }
  // Unrotated, the box is the mesh's bounds grown by the margin.
  btVector3 lo, hi;
  shape.getAabb(btTransform::getIdentity(), lo, hi);
  const Aabb& b = data->mesh.bounds();
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(lo[k], b.lo[k] - shape.getMargin(), 1e-5);
    EXPECT_NEAR(hi[k], b.hi[k] + shape.getMargin(), 1e-5);
  }
}

struct CountingCallback : btTriangleCallback {
  std::vector<int> seen;
  void processTriangle(btVector3*, int, int triangleIndex) override { ++seen[triangleIndex]; }
};

TEST(MeshShape, ProcessAllTrianglesReportsEveryTriangleNearTheBox) {
  const auto data = MeshData::build(gen::makeModel("pipes", 3000));
  MeshShape shape(data);
  const TriangleMesh& mesh = data->mesh;
  std::mt19937_64 rng(kSeed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), size(0.05, 0.5);
  for (int q = 0; q < 50; ++q) {
    const Vec3 c = mesh.bounds().center() + Vec3(u(rng), u(rng), u(rng));
    const Vec3 h(size(rng), size(rng), size(rng));
    CountingCallback cb;
    cb.seen.assign(mesh.triangleCount(), 0);
    const Vec3 lo = c - h, hi = c + h;
    shape.processAllTriangles(&cb, btVector3(static_cast<btScalar>(lo.x()), static_cast<btScalar>(lo.y()),
                                             static_cast<btScalar>(lo.z())),
                              btVector3(static_cast<btScalar>(hi.x()), static_cast<btScalar>(hi.y()),
                                        static_cast<btScalar>(hi.z())));
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
      Aabb tb;
      for (std::uint32_t v : mesh.triangles()[t]) tb.grow(mesh.vertices()[v]);
      const bool overlaps = !((tb.lo.array() > hi.array() + 1e-6).any() ||
                              (tb.hi.array() < lo.array() - 1e-6).any());
      ASSERT_LE(cb.seen[t], 1);
      if (overlaps) {
        ASSERT_EQ(cb.seen[t], 1) << "query " << q << " triangle " << t;
      }
    }
  }
}

TEST(MeshShape, LocalScalingScalesTheBoundsAndKeepsTheSharedTree) {
  const auto data = MeshData::build(gen::makeBox(Vec3(1, 1, 1), 2));
  MeshShape shape(data), other(data);
  shape.setLocalScaling(btVector3(2, 1, 0.5));
  btVector3 lo, hi;
  shape.getAabb(btTransform::getIdentity(), lo, hi);
  EXPECT_NEAR(hi.x() - shape.getMargin(), 2.0, 1e-5);
  EXPECT_NEAR(hi.z() - shape.getMargin(), 0.5, 1e-5);
  EXPECT_NE(&shape.tree(), &other.tree());
  EXPECT_EQ(&other.tree(), &data->tree);
  shape.setLocalScaling(btVector3(1, 1, 1));
  EXPECT_EQ(&shape.tree(), &data->tree);
  EXPECT_THROW(shape.setLocalScaling(btVector3(0, 1, 1)), SettingsError);
  EXPECT_THROW(shape.setLocalScaling(btVector3(1, -1, 1)), SettingsError);
}

TEST(MeshShape, InertiaOfABoxMatchesTheFormula) {
  // A solid 2 x 4 x 6 box of mass 12: I = m/12 (b^2 + c^2) etc. = (52, 40, 20).
  const auto data = MeshData::build(gen::makeBox(Vec3(1, 2, 3), 3));
  MeshShape shape(data);
  btVector3 inertia;
  shape.calculateLocalInertia(12, inertia);
  // In the shape's own axes (the box's axes are its principal axes).
  EXPECT_NEAR(inertia[0], 52.0, 1e-4);
  EXPECT_NEAR(inertia[1], 40.0, 1e-4);
  EXPECT_NEAR(inertia[2], 20.0, 1e-4);
  EXPECT_NEAR(shape.principalTransform().getOrigin().length(), 0.0, 1e-6);
}

}  // namespace
}  // namespace adb
