// rootBoxesOverlap (the error-rate filter) against FCL's box-box test as an independent
// oracle, on random poses around the touching distance, for one box twice and for two
// different boxes, plus hand-made cases.
#include <gtest/gtest.h>

#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision.h>

#include <cmath>
#include <random>

#include "adb/support/benchmark_poses.h"
#include "root_overlap.h"

namespace adb::tradeoff {
namespace {

const Aabb kBox{Vec3(-1.0, -0.5, 0.2), Vec3(2.0, 0.5, 0.6)};  // off-centre, unequal sides

Pose rotZ(double angle, const Vec3& t) {
  return Pose{Eigen::AngleAxisd(angle, Vec3::UnitZ()).toRotationMatrix(), t};
}

// FCL's box is centred on its frame: the frame of `box` (mesh coordinates) posed by `pose`.
fcl::Transform3d boxFrame(const Pose& pose, const Aabb& box) {
  fcl::Transform3d t = fcl::Transform3d::Identity();
  t.linear() = pose.rotation;
  t.translation() = pose.rotation * box.center() + pose.translation;
  return t;
}

TEST(RootOverlap, HandMadeCases) {
  const Aabb cube{Vec3(-1, -1, -1), Vec3(1, 1, 1)};
  EXPECT_TRUE(rootBoxesOverlap(cube, Pose{}, Pose{}));
  EXPECT_TRUE(rootBoxesOverlap(cube, Pose{}, rotZ(0.0, Vec3(1.999, 0, 0))));
  EXPECT_FALSE(rootBoxesOverlap(cube, Pose{}, rotZ(0.0, Vec3(2.001, 0, 0))));
  // Turned 45 degrees: B reaches sqrt(2) along x.
  const double reach = 1.0 + std::sqrt(2.0);
  EXPECT_TRUE(rootBoxesOverlap(cube, Pose{}, rotZ(M_PI / 4, Vec3(reach - 1e-6, 0, 0))));
  EXPECT_FALSE(rootBoxesOverlap(cube, Pose{}, rotZ(M_PI / 4, Vec3(reach + 1e-6, 0, 0))));
}

TEST(RootOverlap, AgreesWithFclBoxBoxOnRandomPoses) {
  const Vec3 size = kBox.extent();
  const auto box = std::make_shared<fcl::Boxd>(size.x(), size.y(), size.z());
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> distance(0.2, 2.0);
  int overlaps = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const PosePair p = benchmarkPoses(kBox, distance(rng), rng);
    fcl::CollisionResultd result;
    fcl::collide(box.get(), boxFrame(p.a, kBox), box.get(), boxFrame(p.b, kBox),
                 fcl::CollisionRequestd(1, false), result);
    const bool ours = rootBoxesOverlap(kBox, p.a, p.b);
    EXPECT_EQ(ours, result.isCollision()) << "pose " << i;
    overlaps += ours ? 1 : 0;
  }
  EXPECT_GT(overlaps, n / 10);
  EXPECT_LT(overlaps, n - n / 10);
}

// Two different boxes (a pair of models): the room-sized box and a small one anywhere in and
// around it, and both at Zachmann's distances in the pair's unit.
TEST(RootOverlap, TwoDifferentBoxesAgreeWithFclBoxBox) {
  const Aabb small{Vec3(-0.2, 0.1, -0.05), Vec3(0.3, 0.25, 0.4)};
  const Vec3 sizeA = kBox.extent(), sizeB = small.extent();
  const auto boxA = std::make_shared<fcl::Boxd>(sizeA.x(), sizeA.y(), sizeA.z());
  const auto boxB = std::make_shared<fcl::Boxd>(sizeB.x(), sizeB.y(), sizeB.z());
  // The inside poses' box grown by half the room on every side: B's centre in and around A.
  const Aabb around{kBox.lo - 0.5 * sizeA, kBox.hi + 0.5 * sizeA};
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> distance(0.2, 2.0);
  int overlaps = 0;
  const int n = 4000;
  for (int i = 0; i < n; ++i) {
    const PosePair p = i % 2 == 0 ? insidePoses(around, small, rng)
                                  : benchmarkPoses(kBox, small, distance(rng), rng);
    fcl::CollisionResultd result;
    fcl::collide(boxA.get(), boxFrame(p.a, kBox), boxB.get(), boxFrame(p.b, small),
                 fcl::CollisionRequestd(1, false), result);
    const bool ours = rootBoxesOverlap(kBox, p.a, small, p.b);
    EXPECT_EQ(ours, result.isCollision()) << "pose " << i;
    EXPECT_EQ(ours, rootBoxesOverlap(small, p.b, kBox, p.a)) << "pose " << i << ": symmetric";
    overlaps += ours ? 1 : 0;
  }
  EXPECT_GT(overlaps, n / 10);
  EXPECT_LT(overlaps, n - n / 10);
}

}  // namespace
}  // namespace adb::tradeoff
