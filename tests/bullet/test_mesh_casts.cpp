// MeshShape's casts through the tree: btCollisionWorld::rayTest and convexSweepTest give the
// hits btBvhTriangleMeshShape gives for the same mesh at the same pose (closest fraction,
// normal, part and triangle index; all hits for the all-hits ray callback), a rotating sweep
// finds the brute-force closest hit, and a fast CCD sphere does not tunnel through a thin
// MeshShape wall.
#include <gtest/gtest.h>

#include <btBulletCollisionCommon.h>
#include <BulletCollision/NarrowPhaseCollision/btRaycastCallback.h>

#include <algorithm>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include "adb/bullet/triangle_arrays.h"
#include "adb/bullet/mesh_shape.h"
#include "adb/support/benchmark_poses.h"
#include "adb/support/mesh_generators.h"
#include "bullet_world.h"

namespace adb {
namespace {

constexpr std::uint64_t kSeed = 20261121;

btVector3 bt(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
                   static_cast<btScalar>(v.z()));
}

btTransform randomPose(std::mt19937_64& rng, double spread) {
  const Eigen::Quaterniond q = randomRotation(rng);
  std::uniform_real_distribution<double> u(-spread, spread);
  return btTransform(btQuaternion(static_cast<btScalar>(q.x()), static_cast<btScalar>(q.y()),
                                  static_cast<btScalar>(q.z()), static_cast<btScalar>(q.w())),
                     bt(Vec3(u(rng), u(rng), u(rng))));
}

/// One collision world per shape kind, the same mesh at the same pose in both: the MeshShape
/// and Bullet's btBvhTriangleMeshShape (quantized BVH, its optimised cast paths).
struct TwoWorlds {
  struct One {
    btDefaultCollisionConfiguration configuration;
    btCollisionDispatcher dispatcher{&configuration};
    btDbvtBroadphase broadphase;
    btCollisionWorld world{&dispatcher, &broadphase, &configuration};
    std::unique_ptr<btCollisionShape> shape;
    btCollisionObject object;
  };
  std::shared_ptr<const MeshData> data;
  TriangleArrays arrays;
  One adb, bvh;

  TwoWorlds(TriangleMesh mesh, const btTransform& pose)
      : data(MeshData::build(mesh)), arrays(mesh) {
    adb.shape = std::make_unique<MeshShape>(data);
    bvh.shape = std::make_unique<btBvhTriangleMeshShape>(arrays.array.get(), true);
    for (One* w : {&adb, &bvh}) {
      w->object.setCollisionShape(w->shape.get());
      w->object.setWorldTransform(pose);
      w->world.addCollisionObject(&w->object);
    }
  }
};

struct RayHit {
  bool hit = false;
  btScalar fraction = 1;
  btVector3 normal{0, 0, 0};
  int part = -2, triangle = -2;
};

struct ClosestRay : btCollisionWorld::ClosestRayResultCallback {
  RayHit h;
  ClosestRay(const btVector3& a, const btVector3& b) : ClosestRayResultCallback(a, b) {}
  btScalar addSingleResult(btCollisionWorld::LocalRayResult& r, bool world) override {
    h.part = r.m_localShapeInfo ? r.m_localShapeInfo->m_shapePart : -1;
    h.triangle = r.m_localShapeInfo ? r.m_localShapeInfo->m_triangleIndex : -1;
    const btScalar f = ClosestRayResultCallback::addSingleResult(r, world);
    h.hit = true;
    h.fraction = m_closestHitFraction;
    h.normal = m_hitNormalWorld;
    return f;
  }
};

struct AllRays : btCollisionWorld::AllHitsRayResultCallback {
  std::vector<std::pair<int, btScalar>> hits;  // (triangle, fraction)
  AllRays(const btVector3& a, const btVector3& b) : AllHitsRayResultCallback(a, b) {}
  btScalar addSingleResult(btCollisionWorld::LocalRayResult& r, bool world) override {
    hits.emplace_back(r.m_localShapeInfo->m_triangleIndex, r.m_hitFraction);
    return AllHitsRayResultCallback::addSingleResult(r, world);
  }
};

struct ClosestSweep : btCollisionWorld::ClosestConvexResultCallback {
  RayHit h;
  btVector3 point{0, 0, 0};
  ClosestSweep() : ClosestConvexResultCallback(btVector3(0, 0, 0), btVector3(0, 0, 0)) {}
  btScalar addSingleResult(btCollisionWorld::LocalConvexResult& r, bool world) override {
    h.part = r.m_localShapeInfo ? r.m_localShapeInfo->m_shapePart : -1;
    h.triangle = r.m_localShapeInfo ? r.m_localShapeInfo->m_triangleIndex : -1;
    const btScalar f = ClosestConvexResultCallback::addSingleResult(r, world);
    h.hit = true;
    h.fraction = m_closestHitFraction;
    h.normal = m_hitNormalWorld;
    point = m_hitPointWorld;
    return f;
  }
};

// Exactly equal, or both absent. A tie (two triangles at the very same fraction, a cast
// through their shared edge) may be reported by either: counted, then bounded by the caller.
void expectSameHit(const RayHit& a, const RayHit& b, int i, int& ties) {
  ASSERT_EQ(a.hit, b.hit) << "cast " << i;
  if (!a.hit) return;
  ASSERT_EQ(a.fraction, b.fraction) << "cast " << i;
  ASSERT_EQ(a.part, b.part) << "cast " << i;
  if (a.triangle != b.triangle) {
    ++ties;
    return;
  }
  ASSERT_EQ(a.normal, b.normal) << "cast " << i;
}

// Rays through the mesh's box from well outside it, in world coordinates.
std::pair<btVector3, btVector3> randomRay(std::mt19937_64& rng, const TwoWorlds& w) {
  btVector3 lo, hi;
  w.adb.shape->getAabb(w.adb.object.getWorldTransform(), lo, hi);
  std::uniform_real_distribution<double> u(0.0, 1.0), s(-1.0, 1.0);
  const btVector3 target = lo + (hi - lo) * bt(Vec3(u(rng), u(rng), u(rng)));
  const btVector3 dir = bt(Vec3(s(rng), s(rng), s(rng)).normalized());
  const btScalar reach = (hi - lo).length();
  return {target - dir * reach, target + dir * reach};
}

TEST(MeshCasts, RayTestMatchesBvhTriangleMeshShape) {
  std::mt19937_64 rng(kSeed);
  for (const char* model : {"knot", "gears", "pipes"}) {
    TwoWorlds w(gen::makeModel(model, 6000), randomPose(rng, 2.0));
    int ties = 0, hits = 0;
    for (int i = 0; i < 300; ++i) {
      auto [from, to] = randomRay(rng, w);
      if (i % 10 == 0) to = from;  // zero length: no hit in either
      ClosestRay a(from, to), b(from, to);
      w.adb.world.rayTest(from, to, a);
      w.bvh.world.rayTest(from, to, b);
      expectSameHit(a.h, b.h, i, ties);
      hits += a.h.hit;
    }
    EXPECT_GT(hits, 40) << model;  // pipes is the sparsest: about 50 of 300 hit
    EXPECT_LE(ties, 3) << model;
  }
}

TEST(MeshCasts, AllHitsRayTestMatchesBvhTriangleMeshShape) {
  std::mt19937_64 rng(kSeed + 1);
  TwoWorlds w(gen::makeModel("pipes", 6000), randomPose(rng, 1.0));
  for (int i = 0; i < 100; ++i) {
    const auto [from, to] = randomRay(rng, w);
    AllRays a(from, to), b(from, to);
    w.adb.world.rayTest(from, to, a);
    w.bvh.world.rayTest(from, to, b);
    std::sort(a.hits.begin(), a.hits.end());
    std::sort(b.hits.begin(), b.hits.end());
    ASSERT_EQ(a.hits, b.hits) << "ray " << i;
  }
}

TEST(MeshCasts, RayFlagsAndAxisParallelRaysMatch) {
  std::mt19937_64 rng(kSeed + 2);
  TwoWorlds w(gen::makeModel("gears", 4000), btTransform::getIdentity());
  std::uniform_real_distribution<double> u(-0.8, 0.8);
  int ties = 0;
  for (int i = 0; i < 300; ++i) {
    btVector3 from = bt(Vec3(u(rng), u(rng), u(rng))), to = from;
    to[i % 3] += btScalar(i % 2 ? 4 : -4);
    from[i % 3] -= btScalar(i % 2 ? 4 : -4);
    ClosestRay a(from, to), b(from, to);
    a.m_flags = b.m_flags = (i % 4 == 0) ? btTriangleRaycastCallback::kF_FilterBackfaces
                                         : btTriangleRaycastCallback::kF_KeepUnflippedNormal;
    w.adb.world.rayTest(from, to, a);
    w.bvh.world.rayTest(from, to, b);
    expectSameHit(a.h, b.h, i, ties);
  }
  EXPECT_LE(ties, 3);
}

// A brute-force reference for a sweep: Bullet's own per-triangle cast on every triangle.
struct BruteSweep : btTriangleConvexcastCallback {
  btScalar best = 1;
  using btTriangleConvexcastCallback::btTriangleConvexcastCallback;
  btScalar reportHit(const btVector3&, const btVector3&, btScalar f, int, int) override {
    best = std::min(best, f);
    return f;
  }
};

// Bullet's cast of `shape` from a to b against one triangle of the mesh posed at `pose`.
btScalar castOne(const btConvexShape* shape, const btTransform& a, const btTransform& b,
                 const btTransform& pose, const TriangleMesh& mesh, int triangle) {
  BruteSweep one(shape, a, b, pose, 0);
  btVector3 c[3];
  for (int k = 0; k < 3; ++k) {
    c[k] = bt(mesh.vertices()[mesh.triangles()[static_cast<std::size_t>(triangle)][k]]);
  }
  one.processTriangle(c, 0, triangle);
  return one.best;
}

TEST(MeshCasts, ConvexSweepsMatchBvhTriangleMeshShape) {
  std::mt19937_64 rng(kSeed + 3);
  btSphereShape sphere(btScalar(0.05));
  btBoxShape box(btVector3(btScalar(0.04), btScalar(0.07), btScalar(0.03)));
  btCapsuleShape capsule(btScalar(0.03), btScalar(0.1));
  btConvexHullShape hull;  // a box whose origin is off its centre: an asymmetric local box
  for (int k = 0; k < 8; ++k) {
    hull.addPoint(btVector3(btScalar(k & 1 ? 0.1 : 0.02), btScalar(k & 2 ? 0.05 : -0.01),
                            btScalar(k & 4 ? 0.03 : -0.06)));
  }
  const std::pair<const char*, btConvexShape*> shapes[] = {
      {"sphere", &sphere}, {"box", &box}, {"capsule", &capsule}, {"hull", &hull}};
  const TriangleMesh mesh = gen::makeModel("knot", 6000);
  TwoWorlds w(mesh, randomPose(rng, 2.0));
  ASSERT_EQ(w.adb.shape->getMargin(), btScalar(0));
  ASSERT_EQ(w.bvh.shape->getMargin(), btScalar(0));
  for (const auto& [name, shape] : shapes) {
    int ties = 0, hits = 0;
    for (int i = 0; i < 120; ++i) {
      const auto [from, to] = randomRay(rng, w);
      btTransform a = randomPose(rng, 0.0), b = a;  // same rotation at both ends
      a.setOrigin(from);
      b.setOrigin(to);
      ClosestSweep ra, rb;
      w.adb.world.convexSweepTest(shape, a, b, ra);
      w.bvh.world.convexSweepTest(shape, a, b, rb);
      const int tiesBefore = ties;
      expectSameHit(ra.h, rb.h, i, ties);
      if (ties != tiesBefore) {
        // A convex reaching a vertex or an edge first touches every triangle sharing it at
        // the very same fraction (same closest feature, same arithmetic): each order picks
        // one of them. The one reported must be such a triangle.
        ASSERT_EQ(castOne(shape, a, b, w.adb.object.getWorldTransform(), mesh, ra.h.triangle),
                  rb.h.fraction)
            << name << " " << i;
      } else if (ra.h.hit) {
        ASSERT_EQ(ra.point, rb.point) << name << " " << i;
      }
      hits += ra.h.hit;
    }
    EXPECT_GT(hits, 30) << name;
    EXPECT_LE(ties, 12) << name;  // measured 0 to 6 of 120 (vertex and edge first contacts)
  }
}

TEST(MeshCasts, RotatingSweepFindsTheBruteForceClosestHit) {
  std::mt19937_64 rng(kSeed + 4);
  const TriangleMesh mesh = gen::makeModel("gears", 3000);
  TwoWorlds w(mesh, randomPose(rng, 1.0));
  btBoxShape box(btVector3(btScalar(0.15), btScalar(0.02), btScalar(0.02)));  // a long stick
  int hits = 0;
  for (int i = 0; i < 40; ++i) {
    const auto [from, to] = randomRay(rng, w);
    btTransform a = randomPose(rng, 0.0), b = randomPose(rng, 0.0);
    a.setOrigin(from);
    b.setOrigin(to);
    ClosestSweep r;
    w.adb.world.convexSweepTest(&box, a, b, r);
    BruteSweep brute(&box, a, b, w.adb.object.getWorldTransform(), w.adb.shape->getMargin());
    for (std::size_t t = 0; t < mesh.triangleCount(); ++t) {
      btVector3 c[3];
      for (int k = 0; k < 3; ++k) c[k] = bt(mesh.vertices()[mesh.triangles()[t][k]]);
      brute.processTriangle(c, 0, static_cast<int>(t));
    }
    ASSERT_EQ(r.h.hit, brute.best < 1) << "sweep " << i;
    if (r.h.hit) {
      ASSERT_EQ(r.h.fraction, brute.best) << "sweep " << i;
    }
    hits += r.h.hit;
  }
  EXPECT_GT(hits, 5);
}

// A thin open wall in the plane x = 0, 2 x 2 units, as a grid of triangles.
TriangleMesh wallMesh(int n) {
  std::vector<Vec3> v;
  std::vector<Triangle> t;
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; j <= n; ++j) v.emplace_back(0.0, -1.0 + 2.0 * i / n, -1.0 + 2.0 * j / n);
  }
  const auto at = [n](int i, int j) { return static_cast<std::uint32_t>(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      t.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      t.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  }
  return TriangleMesh(std::move(v), std::move(t), "wall");
}

// Shoots a small sphere at the wall at 120 m/s (2 m per step, 40 diameters) and returns the
// largest x it reached.
double shootAtWall(bool ccd) {
  test::World w;
  w.world->setGravity(btVector3(0, 0, 0));
  w.add(MeshData::build(wallMesh(16)), 0, btVector3(0, 0, 0));
  btRigidBody* ball = w.add(std::make_unique<btSphereShape>(btScalar(0.025)), 1,
                            btVector3(btScalar(-1.5), btScalar(0.13), btScalar(-0.21)));
  ball->setLinearVelocity(btVector3(120, 0, 0));
  if (ccd) {
    ball->setCcdMotionThreshold(btScalar(0.01));
    ball->setCcdSweptSphereRadius(btScalar(0.02));
  }
  double maxX = -1e9;
  for (int s = 0; s < 30; ++s) {
    w.step();
    maxX = std::max(maxX, static_cast<double>(ball->getWorldTransform().getOrigin().x()));
  }
  return maxX;
}

TEST(MeshCasts, CcdSphereDoesNotTunnelThroughAThinWall) {
  EXPECT_GT(shootAtWall(false), 0.5);  // without CCD it passes straight through
  EXPECT_LT(shootAtWall(true), 0.0);   // with it, it stops in front of the wall
}

}  // namespace
}  // namespace adb
