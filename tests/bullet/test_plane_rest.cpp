// Issue 11's plane target: a pile of 50 concave MeshShape bodies on a btStaticPlaneShape comes
// to rest without sinking. Nothing is put to sleep (a sleeping body would hide both motion and
// sinking), contacts are exact (adb::Dispatcher without a budget), 600 steps of 1/60 s.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cstdio>
#include <memory>
#include <random>
#include <vector>

#include "adb/core/benchmark_poses.h"
#include "adb/core/mesh_generators.h"
#include "bullet_world.h"

namespace adb {
namespace {

using test::World;

// At rest: linear speed below this (m/s). The pile starts 1 to 3 m up and lands within a
// second; 0.05 m/s is what the demo counts as at rest, about 3 mm of motion per step.
constexpr double kRestSpeed = 0.05;
// Penetration into the plane, over the body's size (its bounding-box diagonal): issue 11.
constexpr double kMaxRelativePenetration = 0.01;

// The lowest point of a body's mesh in world y.
double lowestY(const btRigidBody& body, const TriangleMesh& mesh) {
  const btTransform& t = body.getWorldTransform();
  const btVector3 row = t.getBasis().getRow(1);
  const Vec3 r(row.x(), row.y(), row.z());
  double lowest = 1e300;
  for (const Vec3& v : mesh.vertices()) lowest = std::min(lowest, r.dot(v));
  return lowest + t.getOrigin().y();
}

TEST(PlaneRest, FiftyConcaveBodiesRestOnAPlaneWithinOnePercentOfTheirSize) {
  World w;
  // The floor: the plane y = 0; four btBoxShape walls make a 5 x 5 bin on it.
  w.add(std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), btScalar(0)), 0,
        btVector3(0, 0, 0));
  w.add(std::make_unique<btBoxShape>(btVector3(0.25, 1.5, 2.5)), 0, btVector3(2.75, 1.5, 0));
  w.add(std::make_unique<btBoxShape>(btVector3(0.25, 1.5, 2.5)), 0, btVector3(-2.75, 1.5, 0));
  w.add(std::make_unique<btBoxShape>(btVector3(2.5, 1.5, 0.25)), 0, btVector3(0, 1.5, 2.75));
  w.add(std::make_unique<btBoxShape>(btVector3(2.5, 1.5, 0.25)), 0, btVector3(0, 1.5, -2.75));

  // Three concave kinds, ~0.8 across, 560 to 640 triangles each, shared by the bodies of a kind;
  // in their principal frames so that Bullet's inertia is exact.
  const std::vector<std::shared_ptr<const MeshData>> kinds = {
      MeshData::build(gen::makeTorus(0.35, 0.12, 24, 12), {}, ShapeFrame::Principal),
      MeshData::build(gen::makeGear(10, 0.4, 0.32, 0.15, 0.15, 7), {}, ShapeFrame::Principal),
      MeshData::build(gen::makeTorusKnot(2, 3, 0.3, 0.045, 40, 8), {}, ShapeFrame::Principal)};

  // Four by four per layer, 0.95 apart, layers 0.9 apart from 1 m up, random orientations.
  constexpr int kBodies = 50;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  std::vector<btRigidBody*> bodies;
  std::vector<const MeshData*> bodyKind;
  for (int i = 0; i < kBodies; ++i) {
    const MeshData& kind = *kinds[static_cast<std::size_t>(i % 3)];
    const int layer = i / 16, cell = i % 16;
    const btVector3 at(btScalar(-1.425 + 0.95 * (cell % 4) + jitter(rng)),
                       btScalar(1.0 + 0.9 * layer),
                       btScalar(-1.425 + 0.95 * (cell / 4) + jitter(rng)));
    btRigidBody* body = w.add(kinds[static_cast<std::size_t>(i % 3)], 1, at);
    const Eigen::Quaterniond q = randomRotation(rng);
    body->setCenterOfMassTransform(btTransform(
        btQuaternion(btScalar(q.x()), btScalar(q.y()), btScalar(q.z()), btScalar(q.w())), at));
    body->setFriction(btScalar(0.6));
    body->setActivationState(DISABLE_DEACTIVATION);
    bodies.push_back(body);
    bodyKind.push_back(&kind);
  }

  // Worst penetration over the run (relative) and the first step past the limit.
  constexpr int kSteps = 600;
  double worstEver = 0;
  int firstOver = -1;
  for (int step = 1; step <= kSteps; ++step) {
    w.step();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      const double size = bodyKind[i]->mesh.bounds().extent().norm();
      const double depth = std::max(0.0, -lowestY(*bodies[i], bodyKind[i]->mesh)) / size;
      worstEver = std::max(worstEver, depth);
      if (depth > kMaxRelativePenetration && firstOver < 0) firstOver = step;
    }
  }

  double worstEnd = 0, fastest = 0;
  int moving = 0, below = 0, over = 0;
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const btRigidBody& b = *bodies[i];
    const TriangleMesh& mesh = bodyKind[i]->mesh;
    const double size = mesh.bounds().extent().norm();
    const double depth = std::max(0.0, -lowestY(b, mesh));
    const double speed = b.getLinearVelocity().length();
    const double y = b.getWorldTransform().getOrigin().y();
    worstEnd = std::max(worstEnd, depth / size);
    fastest = std::max(fastest, speed);
    moving += speed >= kRestSpeed ? 1 : 0;
    below += y < 0 ? 1 : 0;
    over += depth > kMaxRelativePenetration * size ? 1 : 0;
    EXPECT_LT(speed, kRestSpeed) << "body " << i << " (" << mesh.name() << ") still moving";
    EXPECT_GE(y, 0.0) << "body " << i << " (" << mesh.name() << ") has its centre below the plane";
    EXPECT_LE(depth, kMaxRelativePenetration * size)
        << "body " << i << " (" << mesh.name() << ") is " << depth << " below the plane ("
        << 100 * depth / size << " % of its size " << size << ")";
  }
  std::printf("plane rest: worst penetration at the end %.3f %% of a body's size (%d of %d over "
              "%.0f %%), worst over the run %.3f %%, first over the limit at step %d; fastest "
              "body %.4f m/s (%d moving), %d centres below the plane\n",
              100 * worstEnd, over, kBodies, 100 * kMaxRelativePenetration, 100 * worstEver,
              firstOver, fastest, moving, below);
}

}  // namespace
}  // namespace adb
