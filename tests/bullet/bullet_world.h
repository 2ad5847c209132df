// Test support: a btDiscreteDynamicsWorld with adb's algorithms that owns what it creates,
// stepping, a hash of the bodies' state for reproducibility checks, and a torus lying flat.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <memory>
#include <vector>

#include "adb/bullet/dispatcher.h"
#include "adb/bullet/registration.h"
#include "adb/bullet/mesh_shape.h"
#include "adb/support/mesh_generators.h"

namespace adb::test {

/// Which dispatcher the world uses: adb's (budgeted, scheduled) or Bullet's own with adb's
/// algorithms registered on it (each pair answered at once, exactly).
enum class Dispatch { Adb, Plain };

struct World {
  std::unique_ptr<btDefaultCollisionConfiguration> configuration;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  Dispatcher* adbDispatcher = nullptr;  // the same object under Dispatch::Adb
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  std::unique_ptr<btDiscreteDynamicsWorld> world;
  std::vector<std::unique_ptr<btCollisionShape>> shapes;
  std::vector<std::unique_ptr<btRigidBody>> bodies;

  // ADB_TEST_THREADS=N (the tsan preset sets 2) runs every world's pair queries on N threads
  // where a test left FrameSettings::threads at its default: the tests then check, under the
  // sanitizer, what the threads share.
  static FrameSettings withTestThreads(FrameSettings frame) {
    const char* threads = std::getenv("ADB_TEST_THREADS");
    if (threads != nullptr && frame.threads == FrameSettings{}.threads) {
      frame.threads = std::atoi(threads);
    }
    return frame;
  }

  explicit World(Dispatch dispatch = Dispatch::Adb, const FrameSettings& frame = {}) {
    configuration = std::make_unique<btDefaultCollisionConfiguration>(collisionConstructionInfo());
    if (dispatch == Dispatch::Adb) {
      auto d = std::make_unique<Dispatcher>(configuration.get());
      d->setFrameSettings(withTestThreads(frame));
      adbDispatcher = d.get();
      dispatcher = std::move(d);
    } else {
      dispatcher = std::make_unique<btCollisionDispatcher>(configuration.get());
      registerAlgorithms(*dispatcher, *configuration);
    }
    world = std::make_unique<btDiscreteDynamicsWorld>(dispatcher.get(), &broadphase, &solver,
                                                       configuration.get());
    world->setGravity(btVector3(0, -10, 0));
  }
  ~World() {
    for (auto& b : bodies) world->removeRigidBody(b.get());
  }

  btRigidBody* add(std::shared_ptr<const MeshData> data, btScalar mass, const btVector3& at) {
    return add(std::make_unique<MeshShape>(std::move(data)), mass, at);
  }

  btRigidBody* add(std::unique_ptr<btCollisionShape> shape, btScalar mass, const btVector3& at) {
    btVector3 inertia(0, 0, 0);
    if (mass > 0) shape->calculateLocalInertia(mass, inertia);
    btRigidBody::btRigidBodyConstructionInfo ci(mass, nullptr, shape.get(), inertia);
    ci.m_startWorldTransform.setOrigin(at);
    auto body = std::make_unique<btRigidBody>(ci);
    world->addRigidBody(body.get());
    shapes.push_back(std::move(shape));
    bodies.push_back(std::move(body));
    return bodies.back().get();
  }

  /// One fixed step of 1/60 s.
  void step() { world->stepSimulation(btScalar(1.0 / 60), 1, btScalar(1.0 / 60)); }
};

constexpr double kQuarterTurn = 1.5707963267948966;

/// A torus lying flat: its axis along world y.
inline TriangleMesh flatTorus(double radius, double tube) {
  return gen::transformed(
      gen::makeTorus(radius, tube, 32, 16),
      Pose{Eigen::AngleAxisd(kQuarterTurn, Vec3::UnitX()).toRotationMatrix(), Vec3::Zero()});
}

/// `bodies` concave bodies (tori and 2,000-triangle knots in turn), `perRow` to a row 0.6
/// apart, rows 0.45 above each other from 0.5 up, dropped onto a 10 x 1 x 10 mesh ground:
/// mesh-mesh pairs at once, overlapping from the start, for budgets and threads to matter.
inline void addConcavePile(World& w, int bodies, int perRow) {
  w.add(MeshData::build(gen::makeBox(Vec3(5, 0.5, 5), 4)), 0, btVector3(0, -0.5, 0));
  const auto torus = MeshData::build(flatTorus(0.4, 0.15));
  const auto knot = MeshData::build(gen::makeModel("knot", 2000));
  for (int i = 0; i < bodies; ++i) {
    const btVector3 at(btScalar(-0.3 * (perRow - 1) + 0.6 * (i % perRow)),
                       btScalar(0.5 + 0.45 * (i / perRow)), btScalar(0.1 * (i % 2)));
    btRigidBody* b = w.add(i % 2 ? knot : torus, 1, at);
    b->setActivationState(DISABLE_DEACTIVATION);
  }
}

/// The lowest vertex (world y) of a mesh body.
inline double lowestVertex(const btRigidBody& body) {
  const auto& shape = static_cast<const MeshShape&>(*body.getCollisionShape());
  const btTransform& t = body.getWorldTransform();
  double lowest = std::numeric_limits<double>::infinity();
  for (const Vec3& v : shape.data().mesh.vertices()) {
    const btVector3 w = t * btVector3(btScalar(v.x()), btScalar(v.y()), btScalar(v.z()));
    lowest = std::min(lowest, static_cast<double>(w.y()));
  }
  return lowest;
}

/// FNV-1a over the bytes of every body's transform and velocities.
inline std::uint64_t hashBodies(const std::vector<std::unique_ptr<btRigidBody>>& bodies) {
  std::uint64_t h = 1469598103934665603ull;
  const auto mix = [&](const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 1099511628211ull;
  };
  for (const auto& b : bodies) {
    const btTransform& t = b->getWorldTransform();
    mix(&t, sizeof(t));
    mix(&b->getLinearVelocity(), sizeof(btVector3));
    mix(&b->getAngularVelocity(), sizeof(btVector3));
  }
  return h;
}

}  // namespace adb::test
