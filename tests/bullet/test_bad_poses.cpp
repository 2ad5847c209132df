// A body with a pose adb cannot use (NaN, a scaled basis) in a world of adb meshes: nothing
// leaves the step, the body is named (FrameStats and the callback) once per step, its adb
// pairs are skipped and no NaN reaches the bodies around it.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "adb/bullet/mesh_shape.h"
#include "adb/support/mesh_generators.h"
#include "bullet_world.h"

namespace adb {
namespace {

using test::World;

bool finite(const btRigidBody& b) {
  const btTransform& t = b.getWorldTransform();
  for (int r = 0; r < 3; ++r) {
    if (!std::isfinite(t.getBasis()[r].length2())) return false;
  }
  return std::isfinite(t.getOrigin().length2()) &&
         std::isfinite(b.getLinearVelocity().length2()) &&
         std::isfinite(b.getAngularVelocity().length2());
}

struct BadPoseScene {
  World world;
  btRigidBody* ground;
  std::vector<btRigidBody*> tori;
  std::vector<BadPose> reported;  // by the callback, this step

  BadPoseScene() {
    ground = world.add(std::make_unique<btBoxShape>(btVector3(5, 0.5, 5)), 0,
                       btVector3(0, -0.5, 0));
    const auto torus = MeshData::build(gen::makeTorus(0.5, 0.2, 32, 16));
    // Lying flat, a little apart: each rests on the box floor; the first two overlap.
    for (int i = 0; i < 4; ++i) {
      btRigidBody* b = world.add(torus, 1, btVector3(btScalar(1.3 * i - 2), btScalar(0.19), 0));
      btTransform t = b->getWorldTransform();
      t.setRotation(btQuaternion(btVector3(1, 0, 0), btScalar(M_PI / 2)));
      b->setWorldTransform(t);
      b->setUserPointer(reinterpret_cast<void*>(static_cast<std::uintptr_t>(100 + i)));
      tori.push_back(b);
    }
    world.adbDispatcher->setBadPoseCallback(
        [this](const BadPose& bad) { reported.push_back(bad); });
  }
  void step() {
    reported.clear();
    world.step();
  }
};

TEST(BadPoses, ANaNBodyIsNamedOncePerStepAndItsNeighboursStayFinite) {
  BadPoseScene scene;
  for (int i = 0; i < 30; ++i) scene.step();  // settle
  btRigidBody* bad = scene.tori[1];
  btTransform t = bad->getWorldTransform();
  t.setOrigin(btVector3(std::numeric_limits<btScalar>::quiet_NaN(), 0, 0));
  bad->setWorldTransform(t);
  for (int i = 0; i < 60; ++i) {
    ASSERT_NO_THROW(scene.step());
    const FrameStats& stats = scene.world.adbDispatcher->lastFrameStats();
    // Its pairs with the floor and with torus 0 meet it: named once, by index and pointer.
    ASSERT_EQ(stats.badPoseBodies, 1u) << "step " << i;
    EXPECT_EQ(stats.badPoses[0].body, bad);
    EXPECT_EQ(stats.badPoses[0].bodyIndex, bad->getWorldArrayIndex());
    EXPECT_EQ(stats.badPoses[0].userPointer, bad->getUserPointer());
    EXPECT_EQ(stats.badPoses[0].defect, PoseDefect::NonFinite);
    ASSERT_EQ(scene.reported.size(), 1u);
    EXPECT_EQ(scene.reported[0].body, bad);
    for (btRigidBody* b : scene.tori) {
      if (b != bad) {
        EXPECT_TRUE(finite(*b)) << "torus " << (b - bad);
      }
    }
  }
  // The others still rest on the floor: none fell through or was pushed away.
  for (btRigidBody* b : scene.tori) {
    if (b == bad) continue;
    EXPECT_GT(b->getWorldTransform().getOrigin().y(), 0.1);
    EXPECT_LT(b->getWorldTransform().getOrigin().y(), 0.4);
  }
}

// A NaN velocity makes a NaN pose only at the end of the step: the solver would first carry
// it through the body's adb contacts to the bodies it touches. It is refused like a NaN pose,
// from the step the velocity goes bad.
TEST(BadPoses, ANaNVelocityIsNamedAtOnceAndItsNeighboursStayFinite) {
  BadPoseScene scene;
  btRigidBody* bad = scene.tori[1];
  // It touches torus 0: the contact the NaN would cross.
  btDispatcher& dispatcher = *scene.world.dispatcher;
  const auto touching = [&] {
    for (int i = 0; i < dispatcher.getNumManifolds(); ++i) {
      const btPersistentManifold* m = dispatcher.getManifoldByIndexInternal(i);
      const bool pair = (m->getBody0() == bad && m->getBody1() == scene.tori[0]) ||
                        (m->getBody1() == bad && m->getBody0() == scene.tori[0]);
      if (pair && m->getNumContacts() > 0) return true;
    }
    return false;
  };
  // Settling: the two overlapping tori push apart, and stop touching within about 30 steps.
  for (int i = 0; i < 10; ++i) scene.step();
  ASSERT_TRUE(touching());
  bad->setAngularVelocity(btVector3(0, std::numeric_limits<btScalar>::quiet_NaN(), 0));
  for (int i = 0; i < 10; ++i) {
    ASSERT_NO_THROW(scene.step());
    const FrameStats& stats = scene.world.adbDispatcher->lastFrameStats();
    ASSERT_EQ(stats.badPoseBodies, 1u) << "step " << i;
    EXPECT_EQ(stats.badPoses[0].body, bad);
    EXPECT_EQ(stats.badPoses[0].defect, PoseDefect::NonFinite);
    for (std::size_t k = 0; k < scene.tori.size(); ++k) {
      if (scene.tori[k] != bad) {
        ASSERT_TRUE(finite(*scene.tori[k])) << "torus " << k << ", step " << i;
      }
    }
  }
}

// Bullet's integration re-orthonormalises a dynamic body's basis at the end of a step: the
// scaled basis is written again before every step, as broken user code would.
TEST(BadPoses, AScaledBasisIsRefusedAndTheRestGoesOn) {
  BadPoseScene scene;
  btRigidBody* bad = scene.tori[3];
  for (int i = 0; i < 20; ++i) {
    btTransform t = bad->getWorldTransform();
    t.setBasis(btMatrix3x3(t.getRotation()) * btScalar(2));
    bad->setWorldTransform(t);
    ASSERT_NO_THROW(scene.step());
    const FrameStats& stats = scene.world.adbDispatcher->lastFrameStats();
    ASSERT_EQ(stats.badPoseBodies, 1u) << "step " << i;
    EXPECT_EQ(stats.badPoses[0].defect, PoseDefect::NotOrthonormal);
    EXPECT_EQ(stats.badPoses[0].userPointer, reinterpret_cast<void*>(std::uintptr_t{103}));
  }
  for (btRigidBody* b : scene.tori) EXPECT_TRUE(finite(*b));
}

// How far a btMatrix3x3 is from orthonormal, max |R^T R - I|, computed in double as the core's
// poseDefect does.
double offOrthonormal(const btMatrix3x3& m) {
  double worst = 0.0;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      double dot = 0.0;
      for (int k = 0; k < 3; ++k) dot += double(m[k][i]) * double(m[k][j]);
      worst = std::max(worst, std::abs(dot - (i == j ? 1.0 : 0.0)));
    }
  }
  return worst;
}

// Bullet composes a compound child's world transform in btScalar. In float its basis is off
// orthonormal by up to about 1.3e-6 (measured over 1e6 random pairs of rotations; a single
// basis from a quaternion stays below 0.95e-6), beyond the core's 1e-6: rounding, not a
// defect. A ball dropped onto a static compound's mesh child at such a pose lands on it.
TEST(BadPoses, AChildPoseRoundedInFloatIsUsed) {
  // A body rotation and a child rotation whose product, rounded as Bullet rounds it, is
  // off by more than the core's tolerance (about 1 pair in 5,000 in float; none in double,
  // where the test has nothing to show).
  if (sizeof(btScalar) == sizeof(double)) GTEST_SKIP() << "double bases round below 1e-6";
  std::mt19937_64 rng(7);
  std::normal_distribution<double> n;
  const auto rotation = [&] {
    return btQuaternion(btScalar(n(rng)), btScalar(n(rng)), btScalar(n(rng)), btScalar(n(rng)))
        .normalized();
  };
  btTransform body, child;
  bool found = false;
  for (int i = 0; i < 200000 && !found; ++i) {
    body = btTransform(rotation());
    child = btTransform(rotation());
    found = offOrthonormal((body * child).getBasis()) > 1e-6;
  }
  ASSERT_TRUE(found);

  World world;
  // Bullet's own ball on adb's sphere: the mesh-convex pair sees the child's composed pose.
  auto compound = std::make_unique<btCompoundShape>();
  auto ball = std::make_unique<MeshShape>(MeshData::build(gen::makeSphere(1.0, 6)));
  compound->addChildShape(child, ball.get());
  btRigidBody* fixed = world.add(std::move(compound), 0, btVector3(0, 0, 0));
  world.shapes.push_back(std::move(ball));
  fixed->setWorldTransform(body);
  btRigidBody* dropped =
      world.add(std::make_unique<btSphereShape>(btScalar(0.2)), 1, btVector3(0, 1.25f, 0));
  for (int i = 0; i < 30; ++i) {
    world.step();
    ASSERT_EQ(world.adbDispatcher->lastFrameStats().badPoseBodies, 0u) << "step " << i;
  }
  // Resting on the top at 1.2 (less the icosphere's facets, 0.02, and a contact's depth); a
  // ball the sphere did not hold falls 1.25 m in these 0.5 s, through it.
  EXPECT_GT(dropped->getWorldTransform().getOrigin().y(), 1.1);
}

// The other side of that tolerance: a basis that has drifted (a rotation integrated without
// renormalising, here scaled by 1 + 1e-4) is still refused, not silently straightened.
TEST(BadPoses, ADriftedBasisIsStillRefused) {
  BadPoseScene scene;
  btRigidBody* bad = scene.tori[2];
  btTransform t = bad->getWorldTransform();
  t.setBasis(btMatrix3x3(t.getRotation()) * btScalar(1 + 1e-4));
  bad->setWorldTransform(t);
  scene.step();
  const FrameStats& stats = scene.world.adbDispatcher->lastFrameStats();
  ASSERT_EQ(stats.badPoseBodies, 1u);
  EXPECT_EQ(stats.badPoses[0].body, bad);
  EXPECT_EQ(stats.badPoses[0].defect, PoseDefect::NotOrthonormal);
}

TEST(BadPoses, ACallbackThatThrowsDoesNotEscapeTheStep) {
  BadPoseScene scene;
  scene.world.adbDispatcher->setBadPoseCallback(
      [](const BadPose&) { throw std::runtime_error("user callback"); });
  btTransform t = scene.tori[0]->getWorldTransform();
  t.setOrigin(btVector3(0, std::numeric_limits<btScalar>::infinity(), 0));
  scene.tori[0]->setWorldTransform(t);
  EXPECT_NO_THROW(for (int i = 0; i < 3; ++i) scene.step());
  EXPECT_EQ(scene.world.adbDispatcher->lastFrameStats().badPoseBodies, 1u);
}

}  // namespace
}  // namespace adb
