// A mesh dropped on the other concave grounds Bullet users build: a heightfield and a
// GImpact mesh. Both pairs go through MeshConcaveAlgorithm under adb::Dispatcher's budget.
#include <gtest/gtest.h>

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <btBulletDynamicsCommon.h>

#include <cmath>
#include <vector>

#include "adb/support/mesh_generators.h"
#include "bullet_world.h"

namespace adb {
namespace {

using test::World;

// A torus lying flat (its axis vertical), 0.2 thick: at rest its centre is 0.2 above a
// flat ground at y = 0.
btRigidBody* dropTorus(World& w) {
  const TriangleMesh torus = gen::transformed(
      gen::makeTorus(0.5, 0.2, 32, 16),
      Pose{Eigen::AngleAxisd(M_PI / 2, Vec3::UnitX()).toRotationMatrix(), Vec3::Zero()});
  return w.add(MeshData::build(torus), 1, btVector3(0, 1.0, 0));
}

// Steps 4 s; returns the adb pairs that were not mesh-mesh, over all steps (the body goes to
// sleep at rest, and a sleeping pair is not dispatched).
std::uint32_t settle(World& w) {
  std::uint32_t others = 0;
  for (int step = 0; step < 240; ++step) {
    w.step();
    others += w.adbDispatcher->lastFrameStats().otherPairs;
  }
  return others;
}

TEST(ConcaveGrounds, TorusComesToRestOnAHeightfield) {
  // A flat 9 x 9 heightfield, 1 apart, heights 0 (the arrays outlive the world).
  std::vector<float> heights(81, 0.0f);
  World w;
  // The float-data constructor: the legacy one reads PHY_FLOAT as btScalar, which is double
  // in Bullet's double-precision build (and read past the end of these floats).
  auto field = std::make_unique<btHeightfieldTerrainShape>(9, 9, heights.data(), btScalar(0),
                                                           btScalar(0), 1, false);
  w.add(std::move(field), 0, btVector3(0, 0, 0));
  btRigidBody* body = dropTorus(w);
  EXPECT_GT(settle(w), 0u);  // scheduled under the step's budget
  EXPECT_NEAR(body->getWorldTransform().getOrigin().y(), 0.2, 0.02);
  EXPECT_LT(body->getLinearVelocity().length(), 0.05);
}

TEST(ConcaveGrounds, TorusComesToRestOnAGImpactMesh) {
  btScalar vertices[] = {-5, 0, -5, 5, 0, -5, 5, 0, 5, -5, 0, 5};
  int indices[] = {0, 2, 1, 0, 3, 2};
  btTriangleIndexVertexArray array(2, indices, 3 * sizeof(int), 4, vertices, 3 * sizeof(btScalar));
  World w;
  auto ground = std::make_unique<btGImpactMeshShape>(&array);
  ground->setMargin(0);
  ground->updateBound();
  w.add(std::move(ground), 0, btVector3(0, 0, 0));
  btRigidBody* body = dropTorus(w);
  EXPECT_GT(settle(w), 0u);  // scheduled under the step's budget
  EXPECT_NEAR(body->getWorldTransform().getOrigin().y(), 0.2, 0.02);
  EXPECT_LT(body->getLinearVelocity().length(), 0.05);
}

}  // namespace
}  // namespace adb

namespace adb {
namespace {

// A low-poly furnished room (gen::makeRoom: a shell of two-triangle walls wound inward,
// furniture wound outward) as one static mesh, turned so that its floor is y = 0: its parts
// disagree in winding, so it is two-sided (facing 0); with one sign for the whole, the floor
// turned its back on the bodies on it and 5 of 16 bodies of demos/scenes/robot_room.json fell
// through it. A torus dropped into the room's free corner comes to rest on the floor.
TEST(ConcaveGrounds, TorusComesToRestOnTheFloorOfARoomOfMixedWinding) {
  const Pose upright{Eigen::AngleAxisd(-M_PI / 2, Vec3::UnitX()).toRotationMatrix(),
                     Vec3(0, 1.5, 0)};
  const auto room = MeshData::build(gen::transformed(gen::makeRoom(), upright));
  EXPECT_EQ(room->facing, 0);
  World w;
  w.add(room, 0, btVector3(0, 0, 0));
  btRigidBody* body = dropTorus(w);
  // The free floor by the wall opposite the table and chairs.
  btTransform at = body->getWorldTransform();
  at.setOrigin(btVector3(2.0, 1.0, 2.0));
  body->setWorldTransform(at);
  settle(w);
  EXPECT_NEAR(body->getWorldTransform().getOrigin().y(), 0.2, 0.03);
  EXPECT_LT(body->getLinearVelocity().length(), 0.05);
}

}  // namespace
}  // namespace adb
