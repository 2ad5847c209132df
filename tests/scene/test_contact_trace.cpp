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
