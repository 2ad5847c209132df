// What a pair keeps when the budget gives it nothing (issue 36): its last points, re-measured
// where the bodies are now. A point slides along the surface it touches instead of vanishing
// once its body has slid by the breaking threshold, so a body granted nothing stays on its
// floor.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include "adb/support/mesh_generators.h"
#include "bullet_world.h"

namespace adb {
namespace {

using test::flatTorus;
using test::lowestVertex;
using test::World;

// The contact points between two bodies, over all their manifolds.
int pointsBetween(btDispatcher& dispatcher, const btCollisionObject* a,
                  const btCollisionObject* b) {
  int points = 0;
  for (int m = 0; m < dispatcher.getNumManifolds(); ++m) {
    const btPersistentManifold* manifold = dispatcher.getManifoldByIndexInternal(m);
    const bool between = (manifold->getBody0() == a && manifold->getBody1() == b) ||
                         (manifold->getBody0() == b && manifold->getBody1() == a);
    if (between) points += manifold->getNumContacts();
  }
  return points;
}

TEST(KeptContacts, ABodyGrantedNothingSlidesOnItsKeptPointsAndStaysOnTheGround) {
  // A torus comes to rest on a mesh ground with exact contacts; then the budget is zero and
  // the torus is pushed along the ground without friction at 0.3 m/s: 5 mm a step, past the
  // breaking threshold (0.016 here) in 4 steps. Bullet's refresh dropped each kept point
  // once it had slid that far: within 10 steps the torus held none and fell through the
  // ground. Sliding, its points stay and hold it on the ground for the whole second.
  World w;
  btRigidBody* ground =
      w.add(MeshData::build(gen::makeBox(Vec3(5, 0.5, 5), 4)), 0, btVector3(0, -0.5f, 0));
  btRigidBody* torus = w.add(MeshData::build(flatTorus(0.4, 0.15)), 1, btVector3(0, 0.2f, 0));
  torus->setActivationState(DISABLE_DEACTIVATION);
  // No friction from the start: a kept point keeps the friction it was made with.
  ground->setFriction(0);
  torus->setFriction(0);
  for (int step = 0; step < 120; ++step) w.step();
  ASSERT_GE(pointsBetween(*w.dispatcher, ground, torus), 3) << "resting on exact contacts";
  ASSERT_GT(lowestVertex(*torus), -0.01);

  FrameSettings nothing;
  nothing.budgetNodePairs = 0;
  w.adbDispatcher->setFrameSettings(nothing);
  torus->setLinearVelocity(btVector3(0.3f, 0, 0));
  torus->setAngularVelocity(btVector3(0, 0, 0));
  const btScalar startX = torus->getWorldTransform().getOrigin().x();
  for (int step = 0; step < 60; ++step) {
    w.step();
    EXPECT_EQ(w.adbDispatcher->lastFrameStats().exactContacts, 0u) << "granted nothing";
    EXPECT_GE(pointsBetween(*w.dispatcher, ground, torus), 3) << "step " << step;
    EXPECT_GT(lowestVertex(*torus), -0.01) << "step " << step;
  }
  // It slid (the test is about points that moved): about 0.3 in the second.
  EXPECT_GT(torus->getWorldTransform().getOrigin().x() - startX, 0.2);
}

}  // namespace
}  // namespace adb
