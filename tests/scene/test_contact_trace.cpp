// ContactTrace: a resting contact is matched step after step, a new one is counted new, a
// body's deactivation timer resets are written with their speed and spin.
#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "adb/scene/contact_trace.h"
#include "adb/scene/pile_scene.h"
#include "adb/scene/scene_file.h"
#include "adb/scene/scene_world.h"

namespace adb::scene {
namespace {

namespace fs = std::filesystem;

fs::path freshFolder(const std::string& name) {
  const fs::path folder =
      fs::temp_directory_path() / ("adb_trace_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(folder);
  return folder;
}

int lines(const fs::path& file) {
  std::ifstream in(file);
  int n = 0;
  for (std::string line; std::getline(in, line);) ++n;
  return n;
}

// A ball dropped 0.4 onto a box floor, Bullet's sleeping on: it lands (its contact new), then
// rests on it (the same contact every step) and falls asleep.
TEST(ContactTrace, ARestingContactIsMatchedEveryStepAndTheLandingIsNew) {
  const Scene scene = parseScene(R"({
      "shapes": {"floor": {"type": "box", "half_extents": [1, 0.25, 1]},
                 "ball": {"type": "sphere", "radius": 0.1}},
      "bodies": [{"name": "floor", "shape": "floor", "kind": "static", "position": [0, -0.25, 0]},
                 {"name": "ball", "shape": "ball", "position": [0, 0.5, 0]}],
      "effects": ["dynamics", "sleeping"]})",
                                 "ball.json");
  const fs::path folder = freshFolder("ball");
  SceneWorld world(scene, Backend::Adb);
  const int steps = 240;
  ContactChurn c;
  std::uint64_t resets = 0;
  {
    ContactTrace trace(folder);  // its files are complete once it is gone
    for (int i = 0; i < steps; ++i) {
      world.step();
      trace.record(world);
    }
    c = trace.total();
    resets = trace.resets();
  }
  EXPECT_GE(c.fresh, 1u) << "the landing";
  EXPECT_GT(c.points, 100u) << "resting for most of the run";
  // Bullet's sphere-box algorithm gives no features: matched by nearness, every step but the
  // first of each point.
  EXPECT_GT(double(c.matched) / c.points, 0.95);
  EXPECT_EQ(c.keptId, 0u);
  EXPECT_EQ(world.last().asleep, 1);
  // A header and a row per step; a header and a row per timer reset (the ball falling and
  // bouncing reset it, resting did not).
  EXPECT_EQ(lines(folder / "contact_churn.csv"), 1 + steps);
  EXPECT_EQ(lines(folder / "sleep_resets.csv"), 1 + static_cast<int>(resets));
  fs::remove_all(folder);
}

// adb's mesh-mesh contacts carry their triangles: a gear pile's points keep them from step to
// step for the most part once it has landed.
TEST(ContactTrace, MeshContactsKeepTheirFeatures) {
  PileSpec spec;
  spec.bodies = 9;
  spec.model = "gears";
  spec.trianglesPerBody = 600;
  spec.floor = PileSpec::Floor::Plane;
  const fs::path folder = freshFolder("gears");
  SceneWorld world(makePileScene(spec), Backend::Exact);
  ContactTrace trace(folder);
  for (int i = 0; i < 150; ++i) {
    world.step();
    trace.record(world);
  }
  const ContactChurn& c = trace.total();
  ASSERT_GT(c.points, 0u);
  EXPECT_GT(c.keptId, 0u);
  EXPECT_LE(c.keptId, c.matched);
  EXPECT_LE(c.matched + c.fresh, c.points);
  fs::remove_all(folder);
}

TEST(ContactTrace, AFolderThatCannotBeWrittenIsNamed) {
  EXPECT_THROW(ContactTrace(fs::path("/proc/adb_no_such_folder/trace")), std::exception);
}

}  // namespace
}  // namespace adb::scene

#include <btBulletDynamicsCommon.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>
#include "adb/bullet/dispatcher.h"
#include <limits>
namespace adb::scene {
namespace {
TEST(Experiment, GalleryUnderBudget) {
  Scene scene;
  if (std::getenv("XPILE")) {
    PileSpec spec; spec.bodies = std::getenv("XBODIES") ? std::atoi(std::getenv("XBODIES")) : 50; spec.trianglesPerBody = std::getenv("XTRI") ? std::atoi(std::getenv("XTRI")) : 3000; spec.model = std::getenv("XPILE"); spec.seed = 1;
    spec.floor = std::getenv("XFLOOR") && std::string(std::getenv("XFLOOR")) == "box" ? PileSpec::Floor::Box : PileSpec::Floor::Mesh;
    scene = makePileScene(spec);
  } else {
    scene = loadScene("/work/main/demos/scenes/pile.json");
  }
  scene.world.budget.kind = BudgetSpec::Kind::NodePairs;
  scene.world.budget.nodePairs = std::getenv("XB") ? std::strtoull(std::getenv("XB"), nullptr, 10) : 8496;
  const int steps = std::getenv("XS") ? std::atoi(std::getenv("XS")) : 1200;
  SceneWorld world(scene, Backend::Adb);
  btDiscreteDynamicsWorld* w = world.dynamicsWorld();
  const int sw = std::getenv("XSWITCH") ? std::atoi(std::getenv("XSWITCH")) : -1;
  if (sw >= 0) {
    FrameSettings none = static_cast<Dispatcher*>(w->getDispatcher())->frameSettings();
    none.budgetNodePairs = std::numeric_limits<std::uint64_t>::max();
    none.budgetMicros = std::numeric_limits<double>::infinity();
    static_cast<Dispatcher*>(w->getDispatcher())->setFrameSettings(none);
  }
  for (int i = 0; i < steps; ++i) {
    if (i == sw) {
      FrameSettings zero = static_cast<Dispatcher*>(w->getDispatcher())->frameSettings();
      zero.budgetNodePairs = std::getenv("XZ") ? std::strtoull(std::getenv("XZ"), nullptr, 10) : 0;
      if (std::getenv("XUS")) { zero.budgetNodePairs = std::numeric_limits<std::uint64_t>::max(); zero.budgetMicros = std::atof(std::getenv("XUS")); }
      static_cast<Dispatcher*>(w->getDispatcher())->setFrameSettings(zero);
    }
    if (std::getenv("XLIFT") && i == std::atoi(std::getenv("XLIFT"))) {
      FrameSettings none = static_cast<Dispatcher*>(w->getDispatcher())->frameSettings();
      none.budgetNodePairs = std::numeric_limits<std::uint64_t>::max();
      none.budgetMicros = std::numeric_limits<double>::infinity();
      static_cast<Dispatcher*>(w->getDispatcher())->setFrameSettings(none);
    }
    world.step();
    if (std::getenv("XWHERE") && i % 30 == 0) {
      for (std::size_t bb = 0; bb < world.bodyCount(); ++bb) {
        if (!world.isDynamic(bb)) continue;
        const Vec3 c = world.bodyPose(bb).translation;
        if (c.y() < 0 || std::abs(c.x()) > 2.5 || std::abs(c.z()) > 2.5) std::printf("OUT %d body %zu at %.3f %.3f %.3f\n", i, bb, c.x(), c.y(), c.z());
      }
    }
    if (i % 30 == 0 || (std::getenv("XALL") && i > sw && i < sw + 60)) { const StepRecord& r = world.last(); std::printf("S %d lost %d asleep %d kinetic %.4f pairs %u cut %u reused %u kept %u np %llu\n", i, r.lost, r.asleep, r.kinetic, r.frame.pairs, r.frame.cutPairs, r.frame.reusedPairs, r.frame.otherKeptPairs, (unsigned long long)r.frame.nodePairs); }
    if (std::getenv("XLOW") && i > sw && i < sw + (std::getenv("XLEN") ? std::atoi(std::getenv("XLEN")) : 80)) {
      auto& objs = w->getCollisionObjectArray();
      for (int k = 0; k < objs.size(); ++k) {
        btRigidBody* b = btRigidBody::upcast(objs[k]);
        if (!b || b->getInvMass() == 0) continue;
        const btVector3 o = b->getWorldTransform().getOrigin();
        if (o.y() > (std::getenv("XLOWY") ? std::atof(std::getenv("XLOWY")) : 0.05) && std::abs(o.x()) < 2.4 && std::abs(o.z()) < 2.4) continue;
        std::printf("low %d obj %d at %.3f %.3f %.3f v %.3f %.3f %.3f |", i, k, o.x(), o.y(), o.z(), b->getLinearVelocity().x(), b->getLinearVelocity().y(), b->getLinearVelocity().z());
        btDispatcher* d = w->getDispatcher();
        for (int m = 0; m < d->getNumManifolds(); ++m) {
          const btPersistentManifold* pm = d->getManifoldByIndexInternal(m);
          if (pm->getBody0() != b && pm->getBody1() != b) continue;
          const btCollisionObject* o = pm->getBody0() == b ? pm->getBody1() : pm->getBody0();
          std::printf(" [o%d:%d", o->getWorldArrayIndex(), pm->getNumContacts());
          for (int c = 0; c < pm->getNumContacts(); ++c) std::printf(" %.3f", pm->getContactPoint(c).getDistance());
          std::printf("]");
        }
        std::printf("\n");
      }
    }
    if (i < steps - 60 || i % 10 != 0) continue;
    auto& objs = w->getCollisionObjectArray();
    for (int k = 0; k < objs.size(); ++k) {
      btRigidBody* b = btRigidBody::upcast(objs[k]);
      if (!b || b->getInvMass() == 0) continue;
      const double spin = b->getAngularVelocity().length(), speed = b->getLinearVelocity().length();
      if (spin < 0.6 && speed < 0.3) continue;
      std::printf("step %d obj %d shape %s y %.3f v %.3f w %.3f state %d |", i, k, b->getCollisionShape()->getName(), b->getWorldTransform().getOrigin().y(), speed, spin, b->getActivationState());
      btDispatcher* d = w->getDispatcher();
      for (int m = 0; m < d->getNumManifolds(); ++m) {
        const btPersistentManifold* pm = d->getManifoldByIndexInternal(m);
        if (pm->getBody0() != b && pm->getBody1() != b) continue;
        if (pm->getNumContacts() == 0) continue;
        const btCollisionObject* o = pm->getBody0() == b ? pm->getBody1() : pm->getBody0();
        std::printf(" [o%d:%d", o->getWorldArrayIndex(), pm->getNumContacts());
        for (int c = 0; c < pm->getNumContacts(); ++c) std::printf(" %.3f/%d", pm->getContactPoint(c).getDistance(), pm->getContactPoint(c).m_index0 >= 0 && pm->getContactPoint(c).m_index1 >= 0);
        std::printf("]");
      }
      std::printf("\n");
    }
  }
}
}  // namespace
}  // namespace adb::scene
