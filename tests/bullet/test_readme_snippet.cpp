// The README's Bullet snippet, compiled and run as a test so that it never goes stale: the
// three lines, then a body of the snippet's shape dropped on a mesh ground under the budget.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <adb/support/mesh_generators.h>

// --- README snippet begins ---
#include <adb/bullet/dispatcher.h>
#include <adb/bullet/mesh_shape.h>

bool readmeBulletExample() {
  btDefaultCollisionConfiguration configuration(adb::collisionConstructionInfo());  // pool for adb
  adb::Dispatcher dispatcher(&configuration);  // registers adb's algorithms (contacts, closest points)
  adb::FrameSettings budget;
  budget.budgetMicros = 2000;  // optional: 2 ms per step for all mesh-mesh pairs
  dispatcher.setFrameSettings(budget);

  auto mesh = adb::MeshData::build(adb::gen::makeTorus(0.35, 0.12, 48, 24));  // or your mesh
  adb::MeshShape shape(mesh);  // many bodies may share `mesh`
  // --- README snippet ends ---
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
  world.setGravity(btVector3(0, -10, 0));
  adb::MeshShape ground(adb::MeshData::build(adb::gen::makeBox(adb::Vec3(5, 0.5, 5), 2)));
  btRigidBody floor(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &ground));
  floor.getWorldTransform().setOrigin(btVector3(0, btScalar(-0.5), 0));
  btVector3 inertia;
  shape.calculateLocalInertia(1, inertia);
  btRigidBody body(btRigidBody::btRigidBodyConstructionInfo(1, nullptr, &shape, inertia));
  body.getWorldTransform().setOrigin(btVector3(0, 1, 0));
  world.addRigidBody(&floor);
  world.addRigidBody(&body);
  for (int i = 0; i < 120; ++i) world.stepSimulation(btScalar(1.0 / 60), 1, btScalar(1.0 / 60));
  const bool landed = body.getWorldTransform().getOrigin().y() > 0 &&
                      dispatcher.lastFrameStats().pairs == 1;
  world.removeRigidBody(&body);
  world.removeRigidBody(&floor);
  return shape.getShapeType() == CUSTOM_CONCAVE_SHAPE_TYPE && landed;
}

TEST(Readme, BulletSnippetRuns) { EXPECT_TRUE(readmeBulletExample()); }
