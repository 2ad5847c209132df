// Contacts with identity (issue 35): a mesh-mesh pair's points carry the two triangles that
// made them (m_index0, m_index1), are reduced to its two manifolds' eight by a rule that does
// not depend on the traversal's order, and a pair that does not move keeps the same points.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <tuple>
#include <vector>

#include "adb/bullet/dispatcher.h"
#include "adb/bullet/mesh_shape.h"
#include "adb/bullet/registration.h"
#include "adb/support/mesh_generators.h"

namespace adb {
namespace {

// What identifies a written point, and where it is.
struct WrittenPoint {
  int index0, index1;
  btVector3 onA, onB, normal;
  int manifold;  // which of the dispatcher's manifolds holds it
};

// The second ring lies on its side through the first's tube, 0.05 deep into it.
btTransform ringThroughTube() {
  return btTransform(btQuaternion(btVector3(1, 0, 0), btScalar(SIMD_HALF_PI)),
                     btVector3(btScalar(0.95), btScalar(0.02), 0));
}

// Both rings lie flat, the second 0.3 across and 0.25 up, 0.05 into the first: their tubes
// cross in two long arcs, enough crossing triangle pairs for both manifolds.
btTransform ringsCrossingInTwoArcs() {
  return btTransform(btQuaternion::getIdentity(), btVector3(btScalar(0.3), 0, btScalar(0.25)));
}

// Two tori crossing each other, frozen in place (a collision world: nothing moves them),
// collided step after step by adb's dispatcher with `frame`.
class FrozenPair {
 public:
  FrozenPair(const FrameSettings& frame, const btTransform& second) {
    m_configuration =
        std::make_unique<btDefaultCollisionConfiguration>(collisionConstructionInfo());
    auto dispatcher = std::make_unique<Dispatcher>(m_configuration.get());
    dispatcher->setFrameSettings(frame);
    m_dispatcher = std::move(dispatcher);
    m_world = std::make_unique<btCollisionWorld>(m_dispatcher.get(), &m_broadphase,
                                                 m_configuration.get());
    m_data = MeshData::build(gen::makeTorus(0.5, 0.15, 48, 24));
    m_shape = std::make_unique<MeshShape>(m_data);
    for (int i = 0; i < 2; ++i) {
      auto object = std::make_unique<btCollisionObject>();
      object->setCollisionShape(m_shape.get());
      object->setWorldTransform(i == 0 ? btTransform::getIdentity() : second);
      m_world->addCollisionObject(object.get());
      m_objects.push_back(std::move(object));
    }
  }
  ~FrozenPair() {
    for (auto& o : m_objects) m_world->removeCollisionObject(o.get());
  }

  // Collides once and returns the pair's points.
  std::vector<WrittenPoint> step() {
    m_world->performDiscreteCollisionDetection();
    std::vector<WrittenPoint> points;
    for (int m = 0; m < m_dispatcher->getNumManifolds(); ++m) {
      const btPersistentManifold& manifold = *m_dispatcher->getManifoldByIndexInternal(m);
      for (int i = 0; i < manifold.getNumContacts(); ++i) {
        const btManifoldPoint& p = manifold.getContactPoint(i);
        points.push_back({p.m_index0, p.m_index1, p.m_positionWorldOnA, p.m_positionWorldOnB,
                          p.m_normalWorldOnB, m});
      }
    }
    return points;
  }
  std::size_t triangles() const { return m_data->mesh.triangleCount(); }
  void setFrameSettings(const FrameSettings& frame) {
    static_cast<Dispatcher&>(*m_dispatcher).setFrameSettings(frame);
  }
  const FrameStats& stats() const {
    return static_cast<Dispatcher&>(*m_dispatcher).lastFrameStats();
  }

 private:
  std::unique_ptr<btDefaultCollisionConfiguration> m_configuration;
  std::unique_ptr<btCollisionDispatcher> m_dispatcher;
  btDbvtBroadphase m_broadphase;
  std::unique_ptr<btCollisionWorld> m_world;
  std::shared_ptr<const MeshData> m_data;
  std::unique_ptr<MeshShape> m_shape;
  std::vector<std::unique_ptr<btCollisionObject>> m_objects;
};

TEST(ContactIdentity, AFrozenPairWritesTheSamePointsWithTheSameIdsEveryStep) {
  // Re-queried every step (keepRestingContacts off: the reduction alone must give the same
  // points), and by default (the pair keeps its contacts).
  for (bool keep : {false, true}) {
    SCOPED_TRACE(keep ? "contacts kept" : "queried every step");
    FrameSettings frame;
    frame.keepRestingContacts = keep;
    FrozenPair pair(frame, ringThroughTube());
    const std::vector<WrittenPoint> first = pair.step();
    // A ring through another's tube crosses it on both sides: more than one point, at most
    // the two manifolds' eight, each made by two real triangles.
    ASSERT_GE(first.size(), 2u);
    ASSERT_LE(first.size(), 8u);
    for (const WrittenPoint& p : first) {
      EXPECT_GE(p.index0, 0);
      EXPECT_GE(p.index1, 0);
      EXPECT_LT(static_cast<std::size_t>(p.index0), pair.triangles());
      EXPECT_LT(static_cast<std::size_t>(p.index1), pair.triangles());
    }
    for (int step = 2; step <= 10; ++step) {
      const std::vector<WrittenPoint> now = pair.step();
      ASSERT_EQ(now.size(), first.size()) << "step " << step;
      for (std::size_t i = 0; i < now.size(); ++i) {
        EXPECT_EQ(std::tie(now[i].index0, now[i].index1),
                  std::tie(first[i].index0, first[i].index1))
            << "point " << i << ", step " << step;
        // The same place to rounding (the poses do not change).
        EXPECT_LT((now[i].onA - first[i].onA).length(), 1e-5) << "step " << step;
        EXPECT_LT((now[i].onB - first[i].onB).length(), 1e-5) << "step " << step;
        EXPECT_GT(now[i].normal.dot(first[i].normal), 1 - 1e-6) << "step " << step;
        EXPECT_EQ(now[i].manifold, first[i].manifold) << "step " << step;
      }
      EXPECT_EQ(pair.stats().reusedPairs, keep ? 1u : 0u) << "step " << step;
    }
  }
}

TEST(ContactIdentity, APairRestingOnSeveralRegionsHoldsEightPointsInTwoManifolds) {
  // Two rings crossing in two long arcs (ringsCrossingInTwoArcs). Four points held one or two
  // places of such a contact, and the
  // solver's push there spun piled bodies (docs/bullet-results.md); the pair now writes the
  // deepest point, the points it had, and the widest support, up to four per manifold.
  FrozenPair pair(FrameSettings{}, ringsCrossingInTwoArcs());
  const std::vector<WrittenPoint> points = pair.step();
  std::vector<int> perManifold(2, 0);
  for (const WrittenPoint& p : points) {
    ASSERT_GE(p.manifold, 0);
    ASSERT_LT(p.manifold, 2) << "one pair, two manifolds";
    ++perManifold[static_cast<std::size_t>(p.manifold)];
    EXPECT_GE(p.index0, 0);
    EXPECT_GE(p.index1, 0);
  }
  EXPECT_EQ(perManifold[0], 4);
  EXPECT_GT(perManifold[1], 0);
  EXPECT_LE(perManifold[1], 4);
  // Spread over both arcs: the points reach farther apart than the rings' tube is wide.
  double widest = 0;
  for (const WrittenPoint& p : points) {
    for (const WrittenPoint& q : points) widest = std::max(widest, double((p.onB - q.onB).length()));
  }
  EXPECT_GT(widest, 0.3);
  // Every point pushes the upper ring up and the lower down (Bullet's normal on body 1, the
  // upper ring, points towards body 0), none sideways through a tube.
  for (const WrittenPoint& p : points) EXPECT_LT(p.normal.z(), -0.25);
}

TEST(ContactIdentity, ACutPairFrozenInPlaceKeepsItsExactPointsEveryStep) {
  // Queried every step (the reuse off), exact first, then under a budget of one node pair a
  // step: the query never gets past the roots, and the pair's points must be last step's
  // exact ones, re-measured where they are, not guesses from the roots: a cut never deletes
  // a contact that held a body.
  for (std::uint64_t budget : {1u, 16u, 64u, 256u}) {
  SCOPED_TRACE(budget);
  FrameSettings frame;
  frame.keepRestingContacts = false;
  FrozenPair pair(frame, ringsCrossingInTwoArcs());
  const std::vector<WrittenPoint> exact = pair.step();
  ASSERT_EQ(exact.size(), 8u);
  frame.budgetNodePairs = budget;
  pair.setFrameSettings(frame);
  int cutSteps = 0;
  for (int step = 2; step <= 10; ++step) {
    const std::vector<WrittenPoint> now = pair.step();
    cutSteps += static_cast<int>(pair.stats().cutPairs);
    for (const WrittenPoint& p : exact) {
      const auto same = [&](const WrittenPoint& q) {
        return q.index0 == p.index0 && q.index1 == p.index1 && (q.onB - p.onB).length() < 1e-5;
      };
      EXPECT_TRUE(std::any_of(now.begin(), now.end(), same))
          << "step " << step << ": the point of triangles " << p.index0 << ", " << p.index1
          << " is gone";
    }
  }
  EXPECT_GT(cutSteps, 0);
  }
}

}  // namespace
}  // namespace adb
