// Edge cases of the step's scheduler found in review: a whole pair that costs about the whole
// budget keeps running; a compound's mesh child against a general convex shape keeps the
// result's bodies; a bad-pose callback that queries the world; node-pair budgets with whole
// pairs reproduce bit for bit.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <set>

#include "adb/support/mesh_generators.h"
#include "bullet_world.h"

namespace adb {
namespace {

using test::World;

// A static 40 x 40 grid of 160 x 160 cells and a 1 x 0.2 x 1 box on it: one whole pair.
struct BoxOnGrid {
  World w;
  btRigidBody* box;
  explicit BoxOnGrid(const FrameSettings& settings) : w(test::Dispatch::Adb, settings) {
    w.add(MeshData::build(gen::transformed(
              gen::makeFlatGrid(40, 40, 160, 160),
              Pose{Eigen::AngleAxisd(-M_PI / 2, Vec3::UnitX()).toRotationMatrix(), Vec3::Zero()})),
          0, btVector3(0, 0, 0));
    box = w.add(std::make_unique<btBoxShape>(btVector3(0.5f, 0.1f, 0.5f)), 1,
                btVector3(0, 0.3f, 0));
    box->setActivationState(DISABLE_DEACTIVATION);
  }
};

TEST(SchedulerEdges, AWholePairAsCostlyAsTheBudgetStillRuns) {
  // The pair's need, unbudgeted, once the box rests.
  std::uint64_t need = 0;
  {
    BoxOnGrid exact{FrameSettings{}};
    for (int i = 0; i < 60; ++i) exact.w.step();
    need = exact.w.adbDispatcher->lastFrameStats().neededNodePairs;
  }
  ASSERT_GT(need, 20u);
  // A budget between the need and the need with the estimate's quarter of headroom.
  FrameSettings tight;
  tight.budgetNodePairs = need + need / 8;
  BoxOnGrid scene{tight};
  int ran = 0;
  for (int i = 0; i < 120; ++i) {
    if (i == 60) scene.box->setLinearVelocity(btVector3(3, -3, 0));  // shoved into the grid
    scene.w.step();
    ran += scene.w.adbDispatcher->lastFrameStats().otherKeptPairs == 0 ? 1 : 0;
  }
  EXPECT_GT(ran, 40);  // at least every third step
  EXPECT_GT(scene.box->getWorldTransform().getOrigin().y(), 0.0) << "through the grid";
}

struct PointBodies : btCollisionWorld::ContactResultCallback {
  std::set<const btCollisionObject*> seen;
  int points = 0;
  btScalar addSingleResult(btManifoldPoint&, const btCollisionObjectWrapper* a, int, int,
                           const btCollisionObjectWrapper* b, int, int) override {
    seen.insert(a->getCollisionObject());
    seen.insert(b->getCollisionObject());
    ++points;
    return 0;
  }
};

TEST(SchedulerEdges, ACompoundMeshChildAgainstACylinderNamesBothBodies) {
  // Bullet calls a compound's child as (child, other) with the result made as (other,
  // compound): the GJK path must swap the triangle into the compound's slot of the result.
  for (int order = 0; order < 2; ++order) {
    World w(test::Dispatch::Plain);
    auto compound = std::make_unique<btCompoundShape>();
    auto child = std::make_unique<MeshShape>(MeshData::build(gen::makeBox(Vec3(1, 0.2, 1), 4)));
    compound->addChildShape(btTransform::getIdentity(), child.get());
    w.shapes.push_back(std::move(child));
    btRigidBody* ground = w.add(std::move(compound), 0, btVector3(0, 0, 0));
    btRigidBody* cylinder =
        w.add(std::make_unique<btCylinderShape>(btVector3(0.2f, 0.3f, 0.2f)), 1,
              btVector3(0, 0.45f, 0));
    PointBodies result;
    if (order == 0) {
      w.world->contactPairTest(cylinder, ground, result);
    } else {
      w.world->contactPairTest(ground, cylinder, result);
    }
    EXPECT_GT(result.points, 0) << order;
    EXPECT_EQ(result.seen, (std::set<const btCollisionObject*>{ground, cylinder})) << order;
  }
}

TEST(SchedulerEdges, ABadPoseCallbackMayQueryTheWorld) {
  World w;
  w.add(std::make_unique<btBoxShape>(btVector3(5, 0.5f, 5)), 0, btVector3(0, -0.5f, 0));
  const auto torus = MeshData::build(gen::makeTorus(0.5, 0.2, 24, 12));
  btRigidBody* good = w.add(torus, 1, btVector3(-1.5f, 0.25f, 0));
  btRigidBody* bad = w.add(torus, 1, btVector3(1.5f, 0.25f, 0));
  int calls = 0, points = 0;
  w.adbDispatcher->setBadPoseCallback([&](const BadPose&) {
    ++calls;
    PointBodies r;
    w.world->contactTest(good, r);  // answered at once, not deferred into the step
    points += r.points;
  });
  for (int i = 0; i < 10; ++i) {
    btTransform t = bad->getWorldTransform();
    t.setBasis(btMatrix3x3(t.getRotation()) * btScalar(2));
    bad->setWorldTransform(t);
    ASSERT_NO_THROW(w.step());
  }
  EXPECT_EQ(calls, 10);
  EXPECT_GT(points, 0);
}

std::uint64_t mixedRun() {
  FrameSettings f;
  f.budgetNodePairs = 400;
  World w(test::Dispatch::Adb, f);
  w.add(std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), 0), 0, btVector3(0, 0, 0));
  const auto knot = MeshData::build(gen::makeModel("knot", 1500));
  for (int i = 0; i < 4; ++i) w.add(knot, 1, btVector3(btScalar(i * 0.5), btScalar(1 + i), 0));
  for (int i = 0; i < 4; ++i) {
    w.add(std::make_unique<btBoxShape>(btVector3(0.15f, 0.1f, 0.2f)), 1,
          btVector3(btScalar(i * 0.4 - 0.6), btScalar(3 + i * 0.3), 0.1f));
  }
  for (int i = 0; i < 150; ++i) w.step();
  return test::hashBodies(w.bodies);
}

TEST(SchedulerEdges, NodePairBudgetsWithWholePairsReproduceBitForBit) {
  EXPECT_EQ(mixedRun(), mixedRun());
}

}  // namespace
}  // namespace adb
