// The Bullet layer under abuse: a randomized btDiscreteDynamicsWorld under adb::Dispatcher,
// with and without a node-pair budget, holding every kind of body adb meets (generated meshes,
// degenerate ones, meshes scaled to 1e4 and 1e-3 by setLocalScaling and by their vertices,
// Bullet's primitives with CCD, planes, compounds of meshes) at random poses and velocities,
// some fast. Mid-run one mesh body gets a NaN velocity and another a NaN transform.
// Asserted at every step: nothing throws; no other body's transform or velocities become
// non-finite; only the poisoned bodies are ever named as bad, and each is named; every body
// stays within generous bounds (no explosion). With the node-pair budget, a run repeats bit
// for bit. Not asserted: that nothing falls through the ground. Some bodies do, and a plane
// below catches them: the tiny and the flat ones (no CCD for mesh bodies), thin boxes whose
// centre passes a face (triangles are two-sided to convex shapes, as Bullet's are), and
// under the budget bodies starved of it (docs/reliability.md, "Budget starvation").
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <ostream>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "adb/support/mesh_generators.h"
#include "bullet_world.h"

namespace adb {
namespace {

using test::World;

// The run: 50 random bodies, 4 s of simulated time at 60 Hz. The NaN velocity goes in at the
// first step from kNaNVelocityStep on where a mesh body touches a moving one (that contact is
// what the NaN would cross; the pile is busiest while it forms), at the latest
// kLastNaNVelocityStep; the NaN pose later, at a fixed step, so that each one's aftermath is
// seen on its own and for a second at least.
constexpr int kBodies = 50;
constexpr int kSteps = 240;
constexpr int kNaNVelocityStep = 40;
constexpr int kLastNaNVelocityStep = 120;
constexpr int kNaNPoseStep = 180;
// Launch speeds: most bodies drift, one in five is fast (a bullet through the pile).
constexpr double kSlow = 4.0;
constexpr double kFastMin = 50.0, kFastMax = 300.0;
// Generous bounds. The fastest launch covers 1.2 km in the run and gravity adds 40 m/s, and
// the huge torus lies within 1e4 of the origin: 1e5 m leaves a wide margin. Speeds: 10x the
// fastest launch, for the centre and for the rim (spin times the bounding radius): a 1 mm
// gear hit off-centre legitimately spins at 1e4 to 1e6 rad/s, a 10 km torus barely turns.
constexpr double kMaxDistance = 1e5;
constexpr double kMaxSpeed = 10 * kFastMax;

using Rng = std::mt19937_64;

double uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

btVector3 uniformVector(Rng& rng, double half) {
  return btVector3(btScalar(uniform(rng, -half, half)), btScalar(uniform(rng, -half, half)),
                   btScalar(uniform(rng, -half, half)));
}

btVector3 randomDirection(Rng& rng) {
  std::normal_distribution<double> n;
  const btVector3 v(btScalar(n(rng)), btScalar(n(rng)), btScalar(n(rng)));
  return v.length2() > btScalar(1e-12) ? v.normalized() : btVector3(0, 1, 0);
}

btQuaternion randomRotation(Rng& rng) {
  std::normal_distribution<double> n;
  btQuaternion q(btScalar(n(rng)), btScalar(n(rng)), btScalar(n(rng)), btScalar(n(rng)));
  return q.length2() > btScalar(1e-12) ? q.normalized() : btQuaternion::getIdentity();
}

TriangleMesh scaledMesh(const TriangleMesh& mesh, double scale, const std::string& name) {
  std::vector<Vec3> v = mesh.vertices();
  for (Vec3& x : v) x *= scale;
  return TriangleMesh(std::move(v), mesh.triangles(), name);
}

// The meshes the bodies share, built once per process (the trees cost more than the run).
struct Library {
  std::shared_ptr<const MeshData> torus, gear, knot, box, grid, triangle, sliver, needle;
  std::shared_ptr<const MeshData> hugeTorus, tinyGear;  // scaled by their vertices
  std::shared_ptr<const MeshData> cube;  // a closed 1 m cube, scaled by its shapes

  Library() {
    // Principal frames: dynamic bodies need their centre of mass at the shape's origin.
    const auto principal = [](TriangleMesh m) {
      return MeshData::build(std::move(m), {}, ShapeFrame::Principal);
    };
    torus = principal(gen::makeTorus(0.35, 0.12, 24, 12));
    gear = principal(gen::makeGear(10, 0.4, 0.3, 0.1, 0.15, 4));
    knot = principal(gen::makeTorusKnot(2, 3, 0.5, 0.07, 96, 8));
    box = principal(gen::makeBox(Vec3(0.3, 0.2, 0.25), 2));
    grid = principal(gen::makeFlatGrid(1.0, 0.8, 4, 4));  // open, flat: a thin shell
    triangle = principal(TriangleMesh({{0, 0, 0}, {0.6, 0, 0}, {0, 0.5, 0.1}}, {{0, 1, 2}},
                                      "one triangle"));
    sliver = principal(sliverBox());
    // Only zero-area triangles (segments and a point): a point mass with no surface.
    needle = principal(TriangleMesh({{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}, {0, 0.4, 0}},
                                    {{0, 1, 2}, {0, 0, 3}, {3, 3, 3}}, "needle"));
    hugeTorus = principal(scaledMesh(gen::makeTorus(0.35, 0.12, 24, 12), 1e4, "huge torus"));
    tinyGear = principal(scaledMesh(gen::makeGear(10, 0.4, 0.3, 0.1, 0.15, 4), 1e-3,
                                    "tiny gear"));
    cube = MeshData::build(gen::makeBox(Vec3(0.5, 0.5, 0.5), 4));
  }

  // A closed box with extra triangles along one top edge: degenerate ones (a repeated
  // index, three collinear points) and a sliver 1e-6 high and 0.5 long.
  static TriangleMesh sliverBox() {
    const TriangleMesh box = gen::makeBox(Vec3(0.25, 0.25, 0.25), 2);
    std::vector<Vec3> v = box.vertices();
    std::vector<Triangle> t = box.triangles();
    const auto n = static_cast<std::uint32_t>(v.size());
    v.push_back(Vec3(-0.25, 0.25, 0.25));       // n, n + 1: the edge's ends
    v.push_back(Vec3(0.25, 0.25, 0.25));
    v.push_back(Vec3(0.0, 0.25, 0.25));         // n + 2: its midpoint
    v.push_back(Vec3(0.0, 0.25 + 1e-6, 0.25));  // n + 3: a hair above it
    t.push_back({n, n, n + 1});
    t.push_back({n, n + 2, n + 1});
    t.push_back({n, n + 1, n + 3});
    const TriangleMesh mesh(std::move(v), std::move(t), "sliver box");
    EXPECT_EQ(mesh.report().degenerateTriangles, 2u);
    return mesh;
  }
};

const Library& library() {
  static const Library lib;
  return lib;
}

struct Variant {
  std::uint64_t seed;
  bool budget;  // a node-pair budget, or none (exact contacts everywhere)
};

void PrintTo(const Variant& v, std::ostream* os) {
  *os << "seed " << v.seed << (v.budget ? ", node-pair budget" : ", no budget");
}

std::string variantName(const ::testing::TestParamInfo<Variant>& info) {
  return "seed" + std::to_string(info.param.seed) + (info.param.budget ? "Budget" : "Exact");
}

// The world's node-pair budget in the budgeted variant: about 40 % of what the pile needs once
// formed (8,000 to 13,000 node pairs), so that pairs are cut and whole pairs skipped.
constexpr std::uint64_t kBudgetNodePairs = 4000;

FrameSettings settingsOf(const Variant& v) {
  FrameSettings s;
  if (v.budget) s.budgetNodePairs = kBudgetNodePairs;
  return s;
}

bool finite(const btVector3& v) {
  return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z());
}

bool finite(const btRigidBody& b) {
  const btTransform& t = b.getWorldTransform();
  for (int r = 0; r < 3; ++r) {
    if (!finite(t.getBasis()[r])) return false;
  }
  return finite(t.getOrigin()) && finite(b.getLinearVelocity()) &&
         finite(b.getAngularVelocity());
}

// How far the body's points reach from its centre of mass (its bounding sphere's).
double reach(const btRigidBody& b) {
  btVector3 centre;
  btScalar radius = 0;
  b.getCollisionShape()->getBoundingSphere(centre, radius);
  return centre.length() + radius;
}

// Whether every leaf of `shape` is a MeshShape: all of such a body's pairs are adb's, so a
// NaN in it is adb's to contain. (Bullet's own algorithms pass a NaN on to whatever touches.)
bool meshOnly(const btCollisionShape* shape) {
  if (shape->getShapeType() == CUSTOM_CONCAVE_SHAPE_TYPE) return true;
  if (!shape->isCompound()) return false;
  const auto* compound = static_cast<const btCompoundShape*>(shape);
  for (int i = 0; i < compound->getNumChildShapes(); ++i) {
    if (!meshOnly(compound->getChildShape(i))) return false;
  }
  return compound->getNumChildShapes() > 0;
}

struct AbuseWorld {
  World w;
  std::vector<btRigidBody*> dynamic;
  btRigidBody* hugeTorus = nullptr;
  std::vector<BadPose> reported;  // by the callback, this step

  explicit AbuseWorld(const Variant& v) : w(test::Dispatch::Adb, settingsOf(v)) {
    Rng rng(v.seed);
    const Library& lib = library();
    // The ground: the cube scaled to a slab 10 km wide and 1 m thick (setLocalScaling builds
    // the shape's own tree), its top at y = 0, and a plane 2 m below for what falls through
    // (mesh bodies get no CCD: a 1 mm gear crosses the slab without touching its faces).
    auto ground = std::make_unique<MeshShape>(lib.cube);
    ground->setLocalScaling(btVector3(1e4, 1, 1e4));
    w.add(std::move(ground), 0, btVector3(0, -0.5f, 0));
    w.add(std::make_unique<btStaticPlaneShape>(btVector3(0, 1, 0), btScalar(-2)), 0,
          btVector3(0, 0, 0));
    // A bin of Bullet boxes, 4 x 4 m inside and 2 m high, so that the bodies pile up and
    // touch; a static knot and a ramp (the open grid, stretched) in it.
    for (int side = 0; side < 4; ++side) {
      const btScalar sign = side % 2 ? btScalar(1) : btScalar(-1);
      const bool alongX = side < 2;
      w.add(std::make_unique<btBoxShape>(alongX ? btVector3(2.5f, 1, 0.25f)
                                                : btVector3(0.25f, 1, 2.5f)),
            0, alongX ? btVector3(0, 1, sign * 2.25f) : btVector3(sign * 2.25f, 1, 0));
    }
    place(w.add(std::make_unique<MeshShape>(lib.knot), 0, btVector3(0, 0, 0)),
          btVector3(1, 0.5f, -1), randomRotation(rng));
    auto ramp = std::make_unique<MeshShape>(lib.grid);
    ramp->setLocalScaling(btVector3(2, 2, 1));
    place(w.add(std::move(ramp), 0, btVector3(0, 0, 0)), btVector3(-1, 0.6f, 1),
          btQuaternion(btVector3(1, 0, 0), btScalar(-1.1)));
    // The huge torus lies flat on the ground, the pile inside its hole (2.3 km across): its
    // box overlaps every body, its triangles none but the ground's.
    hugeTorus = w.add(lib.hugeTorus, 1e4, btVector3(0, 0, 0));
    place(hugeTorus, btVector3(btScalar(uniform(rng, -200, 200)), btScalar(0.12e4 + 1),
                               btScalar(uniform(rng, -200, 200))),
          btQuaternion(btVector3(1, 0, 0), btScalar(-test::kQuarterTurn)));
    dynamic.push_back(hugeTorus);
    for (int i = 0; i < kBodies; ++i) addRandomBody(rng, i);
    w.adbDispatcher->setBadPoseCallback(
        [this](const BadPose& bad) { reported.push_back(bad); });
  }

  static void place(btRigidBody* body, const btVector3& at, const btQuaternion& rotation) {
    body->setWorldTransform(btTransform(rotation, at));
    body->setInterpolationWorldTransform(body->getWorldTransform());
  }

  btCollisionShape* keep(std::unique_ptr<btCollisionShape> shape) {
    w.shapes.push_back(std::move(shape));
    return w.shapes.back().get();
  }

  // A MeshShape child for a compound, at a random offset.
  void addMeshChild(btCompoundShape& compound, Rng& rng, std::shared_ptr<const MeshData> data) {
    btCollisionShape* child = keep(std::make_unique<MeshShape>(std::move(data)));
    compound.addChildShape(btTransform(randomRotation(rng), uniformVector(rng, 0.4)), child);
  }

  void addRandomBody(Rng& rng, int index) {
    const Library& lib = library();
    const std::shared_ptr<const MeshData> shared[] = {lib.torus,   lib.gear,     lib.knot,
                                                      lib.box,     lib.grid,     lib.triangle,
                                                      lib.sliver,  lib.needle,   lib.tinyGear};
    constexpr int kShared = 9;
    std::unique_ptr<btCollisionShape> shape;
    btScalar mass = 1;
    bool convex = false;
    const int kind = std::uniform_int_distribution<int>(0, kShared + 5)(rng);
    if (kind < kShared) {
      shape = std::make_unique<MeshShape>(shared[kind]);
      if (shared[kind] == lib.tinyGear) mass = btScalar(1e-3);
    } else if (kind == kShared) {
      // Its own MeshData, as an application loading a mesh per body would have.
      shape = std::make_unique<MeshShape>(MeshData::build(
          gen::makeTorus(uniform(rng, 0.2, 0.5), uniform(rng, 0.05, 0.15), 12, 6), {},
          ShapeFrame::Principal));
    } else if (kind == kShared + 1) {
      // setLocalScaling: tiny (1e-3; on the tiny gear 1e-6), or a non-uniform stretch.
      auto mesh = std::make_unique<MeshShape>(shared[index % kShared]);
      const bool tiny = rng() % 2 == 0;
      mesh->setLocalScaling(tiny ? btVector3(1e-3f, 1e-3f, 1e-3f)
                                 : btVector3(btScalar(uniform(rng, 0.3, 2)),
                                             btScalar(uniform(rng, 0.3, 2)),
                                             btScalar(uniform(rng, 0.3, 2))));
      if (tiny) mass = btScalar(1e-3);
      shape = std::move(mesh);
    } else if (kind == kShared + 2) {
      auto compound = std::make_unique<btCompoundShape>();
      addMeshChild(*compound, rng, lib.torus);
      addMeshChild(*compound, rng, shared[index % kShared]);
      if (rng() % 2 == 0) {  // mixed: a box child too (Bullet's pairs with Bullet's shapes)
        btCollisionShape* box = keep(std::make_unique<btBoxShape>(btVector3(0.2f, 0.1f, 0.15f)));
        compound->addChildShape(btTransform(randomRotation(rng), uniformVector(rng, 0.4)), box);
      }
      shape = std::move(compound);
    } else {
      convex = true;
      switch (kind - kShared - 3) {
        case 0: shape = std::make_unique<btBoxShape>(uniformVector(rng, 0.3).absolute() +
                                                     btVector3(0.05f, 0.05f, 0.05f)); break;
        case 1: shape = std::make_unique<btSphereShape>(btScalar(uniform(rng, 0.05, 0.3))); break;
        default:
          shape = std::make_unique<btCapsuleShape>(btScalar(uniform(rng, 0.05, 0.2)),
                                                   btScalar(uniform(rng, 0.1, 0.5)));
          break;
      }
    }
    btRigidBody* body = w.add(std::move(shape), mass, btVector3(0, 0, 0));
    place(body, btVector3(btScalar(uniform(rng, -1.8, 1.8)), btScalar(uniform(rng, 0.5, 8)),
                          btScalar(uniform(rng, -1.8, 1.8))),
          randomRotation(rng));
    const bool fast = rng() % 5 == 0;
    body->setLinearVelocity(fast ? randomDirection(rng) *
                                       btScalar(uniform(rng, kFastMin, kFastMax))
                                 : uniformVector(rng, kSlow));
    // Spins below Bullet's limit (pi/2 per step, 94 rad/s): above it Bullet's implicit
    // gyroscopic term alone took a free, untouched 1.4 m mesh body from 210 to 2,490 rad/s in
    // one step, which is Bullet's integrator, not collision.
    body->setAngularVelocity(uniformVector(rng, fast ? 50 : 10));
    if (convex) {
      // Bullet sweeps a convex body's CCD sphere through the world, through MeshShape's
      // performConvexcast: the fast ones exercise it.
      btVector3 centre;
      btScalar radius = 0;
      body->getCollisionShape()->getBoundingSphere(centre, radius);
      body->setCcdMotionThreshold(radius);
      body->setCcdSweptSphereRadius(btScalar(0.5) * radius);
    }
    body->setActivationState(DISABLE_DEACTIVATION);  // keep every pair running to the end
    dynamic.push_back(body);
  }

  void step() {
    reported.clear();
    w.step();
  }

  // A dynamic body made only of meshes (all its pairs adb's) that touches the most other
  // dynamic bodies right now (contact points in a manifold), and those bodies; excluded
  // bodies are skipped. nullptr if none touches anything.
  btRigidBody* meshBodyInContact(const std::set<const btCollisionObject*>& excluded,
                                 std::set<const btCollisionObject*>& neighbours) const {
    btRigidBody* best = nullptr;
    std::size_t bestCount = 0;
    for (btRigidBody* b : dynamic) {
      if (b == hugeTorus || excluded.count(b) || !meshOnly(b->getCollisionShape())) continue;
      std::set<const btCollisionObject*> touching;
      bool touches = false;
      for (int i = 0; i < w.dispatcher->getNumManifolds(); ++i) {
        const btPersistentManifold* m = w.dispatcher->getManifoldByIndexInternal(i);
        if (m->getNumContacts() == 0) continue;
        const btCollisionObject* other = m->getBody0() == b   ? m->getBody1()
                                         : m->getBody1() == b ? m->getBody0()
                                                              : nullptr;
        if (!other) continue;
        touches = true;
        if (!other->isStaticOrKinematicObject() && !excluded.count(other)) touching.insert(other);
      }
      if (touches && (!best || touching.size() > bestCount)) {
        best = b;
        bestCount = touching.size();
        neighbours = touching;
      }
    }
    return best;
  }
};

// Runs one world and asserts at every step (see the top of the file); `hash`, if given,
// receives test::hashBodies of the last step.
void runAbuse(const Variant& variant, std::uint64_t* hash = nullptr) {
  AbuseWorld world(variant);
  std::set<const btCollisionObject*> poisoned;
  const btCollisionObject* nanPose = nullptr;
  const btCollisionObject* nanVelocity = nullptr;
  std::set<const btCollisionObject*> velocityNeighbours;
  int nanVelocityStep = -1;
  int nanPoseNamed = 0, nanVelocityNamed = 0, firstVelocityNamed = -1;
  double maxDistance = 0, maxSpeed = 0, maxRimSpeed = 0;
  std::uint64_t cutOrKept = 0;
  for (int step = 0; step < kSteps; ++step) {
    if (step == kNaNPoseStep) {
      std::set<const btCollisionObject*> neighbours;
      btRigidBody* b = world.meshBodyInContact(poisoned, neighbours);
      ASSERT_NE(b, nullptr) << "no mesh body touches anything at step " << step;
      btTransform t = b->getWorldTransform();
      t.setOrigin(btVector3(std::numeric_limits<btScalar>::quiet_NaN(), t.getOrigin().y(),
                            t.getOrigin().z()));
      b->setWorldTransform(t);
      nanPose = b;
      poisoned.insert(b);
    }
    if (step >= kNaNVelocityStep && !nanVelocity) {
      // The one with the most moving neighbours: the solver would carry its NaN to them
      // through their contacts unless adb leaves those contacts out.
      btRigidBody* b = world.meshBodyInContact(poisoned, velocityNeighbours);
      if (b && !velocityNeighbours.empty()) {
        b->setLinearVelocity(btVector3(0, std::numeric_limits<btScalar>::quiet_NaN(), 0));
        nanVelocity = b;
        nanVelocityStep = step;
        poisoned.insert(b);
      } else {
        ASSERT_LT(step, kLastNaNVelocityStep) << "no mesh body touched a moving body";
      }
    }
    ASSERT_NO_THROW(world.step()) << "step " << step;
    const FrameStats& stats = world.w.adbDispatcher->lastFrameStats();
    cutOrKept += stats.cutPairs + stats.otherKeptPairs + stats.lateKeptPairs;
    // Only the poisoned bodies are ever named: the others' poses (float bases, compound
    // children, 1e4 and 1e-3 scales) are all usable.
    for (const BadPose& r : world.reported) {
      ASSERT_TRUE(poisoned.count(r.body))
          << "step " << step << ": unpoisoned body " << r.bodyIndex << " ("
          << r.body->getCollisionShape()->getName() << ") named bad: " << describe(r.defect)
          << "; origin " << r.body->getWorldTransform().getOrigin().x() << " "
          << r.body->getWorldTransform().getOrigin().y() << " "
          << r.body->getWorldTransform().getOrigin().z();
    }
    ASSERT_EQ(stats.badPoseBodies, world.reported.size()) << "step " << step;
    for (std::uint32_t i = 0; i < std::min<std::uint32_t>(stats.badPoseBodies,
                                                          FrameStats::kNamedBadPoses); ++i) {
      const BadPose& bad = stats.badPoses[i];
      EXPECT_EQ(bad.defect, PoseDefect::NonFinite) << "step " << step;
      EXPECT_EQ(bad.bodyIndex, bad.body->getWorldArrayIndex());
      nanPoseNamed += bad.body == nanPose ? 1 : 0;
      if (bad.body == nanVelocity) {
        ++nanVelocityNamed;
        if (firstVelocityNamed < 0) firstVelocityNamed = step;
      }
    }
    if (step == kNaNPoseStep) {
      ASSERT_EQ(nanPoseNamed, 1) << "the body with a NaN transform was not named";
    }
    for (btRigidBody* b : world.dynamic) {
      if (poisoned.count(b)) continue;
      ASSERT_TRUE(finite(*b)) << "step " << step << ": body " << b->getWorldArrayIndex()
                              << " caught a NaN (neighbour of the NaN velocity: "
                              << velocityNeighbours.count(b) << ")";
      maxDistance = std::max<double>(maxDistance, b->getWorldTransform().getOrigin().length());
      maxSpeed = std::max<double>(maxSpeed, b->getLinearVelocity().length());
      maxRimSpeed = std::max<double>(maxRimSpeed, b->getAngularVelocity().length() * reach(*b));
    }
    ASSERT_LT(maxDistance, kMaxDistance) << "step " << step;
    ASSERT_LT(maxSpeed, kMaxSpeed) << "step " << step;
    ASSERT_LT(maxRimSpeed, kMaxSpeed) << "step " << step;
  }
  // Both poisoned bodies are named from the step they went bad to the end: Bullet stops
  // simulating a body whose box is not finite but keeps its broadphase pairs, which meet it.
  EXPECT_EQ(firstVelocityNamed, nanVelocityStep);
  EXPECT_EQ(nanPoseNamed, kSteps - kNaNPoseStep);
  EXPECT_EQ(nanVelocityNamed, kSteps - nanVelocityStep);
  // The budgeted variant did work under a binding budget; the exact one never cut.
  if (variant.budget) {
    EXPECT_GT(cutOrKept, 0u);
  } else {
    EXPECT_EQ(cutOrKept, 0u);
  }
  std::printf("NaN velocity at step %d (%zu moving neighbours); max distance %.3g m, speed "
              "%.3g m/s, rim speed %.3g m/s; cut or kept pairs %llu\n",
              nanVelocityStep, velocityNeighbours.size(), maxDistance, maxSpeed, maxRimSpeed,
              static_cast<unsigned long long>(cutOrKept));
  if (hash) *hash = test::hashBodies(world.w.bodies);
}

class Abuse : public ::testing::TestWithParam<Variant> {};

TEST_P(Abuse, NaNsStayWithTheirBodiesAndNothingExplodes) { runAbuse(GetParam()); }

// A node-pair budget makes a step reproducible bit for bit, NaNs, cut pairs and all.
TEST(AbuseRepeat, ABudgetedRunRepeatsBitForBit) {
  std::uint64_t first = 0, second = 1;
  ASSERT_NO_FATAL_FAILURE(runAbuse(Variant{2, true}, &first));
  ASSERT_NO_FATAL_FAILURE(runAbuse(Variant{2, true}, &second));
  EXPECT_EQ(first, second);
}


INSTANTIATE_TEST_SUITE_P(RandomWorlds, Abuse,
                         ::testing::Values(Variant{1, false}, Variant{1, true}, Variant{2, false},
                                           Variant{2, true}, Variant{3, false}, Variant{3, true}),
                         variantName);

}  // namespace
}  // namespace adb
