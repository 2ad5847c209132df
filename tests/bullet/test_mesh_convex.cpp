// MeshConvexAlgorithm against Bullet's own btConvexConcaveCollisionAlgorithm on a
// btBvhTriangleMeshShape of the same mesh (the independent oracle), on poses of resting
// contact at a known depth.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "adb/support/mesh_generators.h"
#include "shared/pair_kind_scene.h"

namespace adb {
namespace {

using tools::ConvexKind;

// Closed-form kinds (box, wall, sphere, capsule) are exact per triangle; the others run
// Bullet's GJK/EPA per triangle on both sides.
bool closedForm(ConvexKind kind) {
  return kind == ConvexKind::Box || kind == ConvexKind::Wall || kind == ConvexKind::Sphere ||
         kind == ConvexKind::Capsule;
}

class MeshConvexAgainstBullet : public ::testing::TestWithParam<ConvexKind> {};

// Every pose rests 1 % of a small body's size deep (kPenetration of pair_kind_scene.cpp):
// adb finds the contact; where its test is closed-form, at least that deep, never
// shallower than Bullet's answer by a tenth of the resting depth, and never deeper than
// Bullet's answer or the resting depth, whichever is larger, by more than 10 %. For
// cylinders and hulls both sides run GJK/EPA per triangle and differ either way at some
// poses (docs/bullet-results.md): only the contact itself is checked. Bullet rounds a box's corners by its
// margin: both sides get a small margin so that they see the same shape. Bullet's
// manifold, fed point by point, can lose its deepest point to a shallower one nearby; adb
// keeps the deepest, so Bullet is the oracle for "not deeper", and for "not shallower" only
// where it found depth.
TEST_P(MeshConvexAgainstBullet, FindsEveryRestingContactAsDeepAsBullet) {
  const ConvexKind kind = GetParam();
  const TriangleMesh mesh = gen::makeModel("knot", 6000);
  const double resting = 0.01 * 0.05 * mesh.bounds().extent().norm();
  const double tolerance = 0.1 * resting;
  auto adb = tools::makePairWorld(mesh, kind, true);
  auto bullet = tools::makePairWorld(mesh, kind, false);
  for (auto* w : {adb.get(), bullet.get()}) w->convexShape->setMargin(btScalar(1e-4));
  const auto poses = tools::surfacePoses(
      mesh, static_cast<const btConvexShape&>(*adb->convexShape), kind, 48, 11);
  int pose = 0, bulletFoundDepth = 0;
  for (const auto& [meshPose, convexPose] : poses) {
    adb->collide(meshPose, convexPose);
    bullet->collide(meshPose, convexPose);
    const double ours = adb->deepestPenetration(), theirs = bullet->deepestPenetration();
    SCOPED_TRACE(std::string(tools::kindName(kind)) + " pose " + std::to_string(pose++) +
                 ": adb " + std::to_string(ours) + ", Bullet " + std::to_string(theirs));
    EXPECT_GT(adb->contactPoints(), 0);
    if (closedForm(kind)) {
      EXPECT_GE(ours, resting * (1 - 1e-3));
      EXPECT_GE(ours, theirs - tolerance);
      EXPECT_LE(ours, 1.1 * std::max(theirs, resting));
    }
    bulletFoundDepth += theirs > 0.5 * resting;
  }
  EXPECT_GT(bulletFoundDepth, 24);  // the oracle had something to say
}

INSTANTIATE_TEST_SUITE_P(Kinds, MeshConvexAgainstBullet,
                         ::testing::Values(ConvexKind::Box, ConvexKind::Wall, ConvexKind::Sphere,
                                           ConvexKind::Capsule, ConvexKind::Cylinder,
                                           ConvexKind::Hull),
                         [](const auto& kind) { return std::string(tools::kindName(kind.param)); });

}  // namespace
}  // namespace adb
