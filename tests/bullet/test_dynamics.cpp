// MeshShape bodies in a real btDiscreteDynamicsWorld: a concave mesh dropped on a mesh ground
// comes to rest without falling through; contactPairTest reports contacts; registration
// refuses a pool too small. Worlds use adb::Dispatcher without a budget unless a test says
// Dispatch::Plain (Bullet's dispatcher with adb's algorithms registered).
#include <gtest/gtest.h>

#include <LinearMath/btPoolAllocator.h>
#include <btBulletDynamicsCommon.h>

#include <memory>

#include "adb/support/mesh_generators.h"
#include "bullet_world.h"

namespace adb {
namespace {

using test::Dispatch;
using test::World;

class DynamicsBothDispatchers : public ::testing::TestWithParam<Dispatch> {};

TEST_P(DynamicsBothDispatchers, TorusDroppedOnAMeshGroundComesToRest) {
  World w(GetParam());
  // Ground: a 10 x 1 x 10 box mesh whose top face is y = 0.
  w.add(MeshData::build(gen::makeBox(Vec3(5, 0.5, 5), 4)), 0, btVector3(0, -0.5, 0));
  // A torus lying flat (its axis along y after the mesh's own z axis is turned up).
  const TriangleMesh torus = gen::transformed(
      gen::makeTorus(0.5, 0.2, 32, 16),
      Pose{Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()).toRotationMatrix(), Vec3::Zero()});
  btRigidBody* body = w.add(MeshData::build(torus), 1, btVector3(0, 1.0, 0));
  for (int step = 0; step < 240; ++step) w.world->stepSimulation(btScalar(1.0 / 60), 1, btScalar(1.0 / 60));
  const btVector3 p = body->getWorldTransform().getOrigin();
  // Resting on its flat side, the torus centre sits at its tube radius above the ground.
  // Tolerance: 10 % of the tube radius for penetration and solver slop.
  EXPECT_NEAR(p.y(), 0.2, 0.02) << "final height";
  EXPECT_LT(body->getLinearVelocity().length(), 0.05);
}

INSTANTIATE_TEST_SUITE_P(Dispatchers, DynamicsBothDispatchers,
                         ::testing::Values(Dispatch::Adb, Dispatch::Plain),
                         [](const auto& param) {
                           return param.param == Dispatch::Adb ? "AdbDispatcher" : "Plain";
                         });

TEST(Dynamics, ConvexShapesRestOnAMeshGround) {
  // A box (half 0.3) and a sphere (radius 0.25) dropped on a mesh ground: the algorithm for
  // MeshShape vs convex shapes (Bullet's own default would take the mesh for an SDF shape).
  World w;
  w.add(MeshData::build(gen::makeBox(Vec3(5, 0.5, 5), 4)), 0, btVector3(0, -0.5, 0));
  btRigidBody* box = w.add(std::make_unique<btBoxShape>(btVector3(btScalar(0.3), btScalar(0.3),
                                                                  btScalar(0.3))),
                           1, btVector3(-1, 1, 0));
  btRigidBody* ball = w.add(std::make_unique<btSphereShape>(btScalar(0.25)), 1, btVector3(1, 1, 0));
  for (int step = 0; step < 240; ++step) {
    w.world->stepSimulation(btScalar(1.0 / 60), 1, btScalar(1.0 / 60));
  }
  // Resting heights, within 5 % of the size: solver slop and the 0.04 collision margins.
  EXPECT_NEAR(box->getWorldTransform().getOrigin().y(), 0.3, 0.03);
  EXPECT_NEAR(ball->getWorldTransform().getOrigin().y(), 0.25, 0.03);
  EXPECT_LT(box->getLinearVelocity().length(), 0.05);
}

TEST(Dynamics, TorusDroppedOnAStaticPlaneComesToRest) {
  World w;
  w.add(std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), btScalar(0)), 0,
        btVector3(0, 0, 0));
  const TriangleMesh torus = gen::transformed(
      gen::makeTorus(0.5, 0.2, 32, 16),
      Pose{Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()).toRotationMatrix(), Vec3::Zero()});
  // Dropped tilted, so it lands on an edge and has to settle flat.
  btRigidBody* body = w.add(MeshData::build(torus), 1, btVector3(0, 1.0, 0));
  btTransform tilted = body->getWorldTransform();
  tilted.setRotation(btQuaternion(btVector3(1, 0, 0), btScalar(0.4)));
  body->setWorldTransform(tilted);
  for (int step = 0; step < 300; ++step) {
    w.world->stepSimulation(btScalar(1.0 / 60), 1, btScalar(1.0 / 60));
  }
  // Flat on the plane: the centre at the tube radius (+-10 %), at rest.
  EXPECT_NEAR(body->getWorldTransform().getOrigin().y(), 0.2, 0.02);
  EXPECT_LT(body->getLinearVelocity().length(), 0.05);
}

TEST(Dynamics, TorusDroppedOnABvhTriangleMeshGroundComesToRest) {
  // The ground most Bullet users have: a static btBvhTriangleMeshShape, two triangles. The
  // arrays it reads are declared first, so they outlive the world.
  btScalar vertices[] = {-5, 0, -5, 5, 0, -5, 5, 0, 5, -5, 0, 5};
  int indices[] = {0, 2, 1, 0, 3, 2};  // counter-clockwise seen from above
  btTriangleIndexVertexArray array(2, indices, 3 * sizeof(int), 4, vertices, 3 * sizeof(btScalar));
  World w;
  w.add(std::make_unique<btBvhTriangleMeshShape>(&array, true), 0, btVector3(0, 0, 0));
  const TriangleMesh torus = gen::transformed(
      gen::makeTorus(0.5, 0.2, 32, 16),
      Pose{Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()).toRotationMatrix(), Vec3::Zero()});
  btRigidBody* body = w.add(MeshData::build(torus), 1, btVector3(0, 1.0, 0));
  for (int step = 0; step < 240; ++step) {
    w.world->stepSimulation(btScalar(1.0 / 60), 1, btScalar(1.0 / 60));
  }
  EXPECT_NEAR(body->getWorldTransform().getOrigin().y(), 0.2, 0.02);
  EXPECT_LT(body->getLinearVelocity().length(), 0.05);
}

std::uint64_t simulateTumblingPair() {
  World w;
  w.add(MeshData::build(gen::makeBox(Vec3(5, 0.5, 5), 4)), 0, btVector3(0, -0.5, 0));
  const auto knot = MeshData::build(gen::makeModel("knot", 3000));
  btRigidBody* a = w.add(knot, 1, btVector3(0, 1.5, 0));
  btRigidBody* b = w.add(knot, 1, btVector3(btScalar(0.4), 3, btScalar(0.2)));
  a->setAngularVelocity(btVector3(1, 2, 0));
  b->setAngularVelocity(btVector3(0, -1, 3));
  for (int step = 0; step < 120; ++step) {
    w.world->stepSimulation(btScalar(1.0 / 60), 1, btScalar(1.0 / 60));
  }
  return test::hashBodies(w.bodies);
}

TEST(Dynamics, SameSceneTwiceGivesBitIdenticalTrajectories) {
  // Exact contacts involve no clock: two runs agree to the bit (a hash of every transform and
  // velocity after 2 s of two knots tumbling onto a mesh ground and onto each other).
  EXPECT_EQ(simulateTumblingPair(), simulateTumblingPair());
}

// A body whose transform is not a rotation (here scaled by 2, as a broken integrator or user
// code might leave it) makes adb refuse the pose; that must not escape Bullet's step, under
// either dispatcher: the pair gets no contacts that step, the other pairs go on.
TEST(Dynamics, ABodyWithABadPoseThrowsNothingOutOfTheStep) {
  for (test::Dispatch dispatch : {test::Dispatch::Adb, test::Dispatch::Plain}) {
    World w(dispatch);
    w.world->setGravity(btVector3(0, 0, 0));
    const auto torus = MeshData::build(gen::makeTorus(0.5, 0.2, 32, 16));
    w.add(torus, 1, btVector3(0, 0, 0));
    btRigidBody* bad = w.add(torus, 1, btVector3(btScalar(0.3), 0, 0));  // overlapping: a real pair
    btTransform t = bad->getWorldTransform();
    t.setBasis(t.getBasis() * btScalar(2));
    bad->setWorldTransform(t);
    EXPECT_NO_THROW(for (int i = 0; i < 3; ++i) w.step()) << static_cast<int>(dispatch);
  }
}

TEST(Dynamics, MeshesThrownAtEachOtherConserveMomentum) {
  World w;
  w.world->setGravity(btVector3(0, 0, 0));
  const auto torus = MeshData::build(gen::makeTorus(0.5, 0.2, 32, 16));
  btRigidBody* a = w.add(torus, 1, btVector3(-1.5, 0, 0));
  btRigidBody* b = w.add(torus, 2, btVector3(1.5, btScalar(0.3), 0));
  a->setLinearVelocity(btVector3(3, 0, 0));
  b->setLinearVelocity(btVector3(-1, 0, 0));
  const btVector3 before = a->getLinearVelocity() * 1 + b->getLinearVelocity() * 2;
  bool touched = false;
  for (int step = 0; step < 120; ++step) {
    w.world->stepSimulation(btScalar(1.0 / 60), 1, btScalar(1.0 / 60));
    touched = touched || w.dispatcher->getNumManifolds() > 0;
  }
  const btVector3 after = a->getLinearVelocity() * 1 + b->getLinearVelocity() * 2;
  ASSERT_TRUE(touched);
  // They met and bounced: A no longer moves at its initial 3 units/s.
  EXPECT_LT(a->getLinearVelocity().x(), 2.5);
  // Momentum (1 x 3 + 2 x -1 = 1 along x) within 1 % of its magnitude: the solver applies
  // equal and opposite impulses; the slack covers float rounding over 120 steps.
  EXPECT_NEAR((after - before).length(), 0.0, 0.01 * before.length());
}

TEST(Dynamics, ContactPairTestReportsContacts) {
  World w;
  const auto box = MeshData::build(gen::makeBox(Vec3(0.5, 0.5, 0.5), 2));
  btRigidBody* a = w.add(box, 0, btVector3(0, 0, 0));
  btRigidBody* b = w.add(box, 0, btVector3(btScalar(0.9), btScalar(0.1), 0));  // overlapping by 0.1
  struct Count : btCollisionWorld::ContactResultCallback {
    int points = 0;
    btScalar deepest = 0;
    btScalar addSingleResult(btManifoldPoint& cp, const btCollisionObjectWrapper*, int, int,
                             const btCollisionObjectWrapper*, int, int) override {
      ++points;
      deepest = std::min(deepest, cp.getDistance());
      return 0;
    }
  } count;
  w.world->contactPairTest(a, b, count);
  EXPECT_GT(count.points, 0);
  EXPECT_NEAR(count.deepest, -0.1, 0.02);
}

TEST(Dynamics, DefaultAlgorithmPoolHoldsTheAlgorithm) {
  // registerAlgorithms refuses a pool whose elements are smaller than MeshMeshAlgorithm (a
  // release-build Bullet would overrun them). Today Bullet's default elements are larger, so
  // a default configuration works; this fails if the algorithm outgrows them.
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher(&configuration);
  EXPECT_GE(configuration.getCollisionAlgorithmPool()->getElementSize(),
            static_cast<int>(algorithmPoolElementSize()));
  EXPECT_NO_THROW(registerAlgorithms(dispatcher, configuration));
}

}  // namespace
}  // namespace adb
