// SceneWorld: the gallery scenes run, the runner builds only what a scene's effects ask for,
// overlap events agree with exact boolean queries frame by frame, the effects' switches do
// what they say, and the recorder writes what it promises.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "adb/bullet/mesh_shape.h"
#include "adb/core/query.h"
#include "adb/scene/recorder.h"
#include "adb/scene/scene_file.h"
#include "adb/scene/scene_models.h"
#include "adb/scene/scene_world.h"
#include "adb/support/mesh_generators.h"

namespace adb::scene {
namespace {

const std::filesystem::path kGallery = ADB_SCENES_DIR;

Scene gallery(const std::string& name) { return loadScene(kGallery / name); }

bool finite(const Pose& p) { return p.rotation.allFinite() && p.translation.allFinite(); }

// A scene of one body pair to drive the effect switches.
Scene parsed(const std::string& text) { return parseScene(text, "test.json"); }

TEST(SceneWorld, EveryGallerySceneRunsAFewStepsWithEveryBackend) {
  int scenes = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kGallery)) {
    if (entry.path().extension() != ".json") continue;
    ++scenes;
    for (Backend backend : {Backend::Adb, Backend::Exact, Backend::GImpact}) {
      SCOPED_TRACE(entry.path().filename().string() + " " + toString(backend));
      SceneWorld world(loadScene(entry.path()), backend);
      for (int i = 0; i < 4; ++i) {
        const StepRecord& r = world.step();
        EXPECT_TRUE(std::isfinite(r.seconds) && std::isfinite(r.energy) &&
                    std::isfinite(r.penetration));
        EXPECT_GE(r.meanConfidence, 0.0);
        EXPECT_LE(r.meanConfidence, 1.0);
      }
      for (std::size_t b = 0; b < world.bodyCount(); ++b) EXPECT_TRUE(finite(world.bodyPose(b)));
    }
  }
  EXPECT_GE(scenes, 6);
}

TEST(SceneWorld, AnOverlapSceneBuildsNoDynamicsWorldAndNoContacts) {
  SceneWorld world(gallery("assembly_path.json"), Backend::Adb);
  const BuildReport& b = world.built();
  EXPECT_FALSE(b.dynamicsWorld);
  EXPECT_FALSE(b.solver);
  EXPECT_FALSE(b.rigidBodies);
  EXPECT_FALSE(b.contactGeneration);
  EXPECT_TRUE(b.booleanQueries);
  EXPECT_EQ(world.dynamicsWorld(), nullptr);
  EXPECT_EQ(b.describe(),
            "btCollisionWorld, boolean queries, no contacts, no solver, no rigid bodies, "
            "per-step budget");
  for (int i = 0; i < 90; ++i) world.step();  // the part is on the plug by now
  EXPECT_EQ(world.collisionWorld().getDispatcher()->getNumManifolds(), 0);
  EXPECT_TRUE(world.contacts().empty());
  const btCollisionObjectArray& objects = world.collisionWorld().getCollisionObjectArray();
  for (int i = 0; i < objects.size(); ++i) EXPECT_EQ(btRigidBody::upcast(objects[i]), nullptr);
}

TEST(SceneWorld, AContactsSceneHasContactsButNoSolver) {
  SceneWorld world(gallery("gears_contacts.json"), Backend::Adb);
  EXPECT_FALSE(world.built().dynamicsWorld);
  EXPECT_FALSE(world.built().solver);
  EXPECT_TRUE(world.built().contactGeneration);
  int withContacts = 0;
  for (int i = 0; i < 60; ++i) {
    withContacts += world.step().contacts > 0 ? 1 : 0;
    // The follower runs 4 degrees ahead of the mesh position: its flanks press into the
    // driver's, in the zone where the teeth engage, around the midpoint of the centres.
    for (const ContactPoint& c : world.contacts()) {
      EXPECT_LT(std::abs(c.position.x()), 0.15);
      EXPECT_LT(std::abs(c.position.y()), 0.3);
      EXPECT_GE(c.depth, 0.0);
    }
  }
  // A tooth pair is pressed together for part of each tooth's passage (measured: 27 of 60
  // steps): contacts come and go as the teeth do.
  EXPECT_GE(withContacts, 20);
  EXPECT_LT(withContacts, 60);
}

// The overlap state after every step against adb's exact query on independently built trees
// at the same poses. The exact backend must agree everywhere; the adb backend (k_min 5 under a
// node-pair budget) wherever it is at least 99 % sure, and on 97 % of the frames in all;
// GImpact, a peer with margins of its own, on 97 % of the frames.
TEST(SceneWorld, OverlapEventsMatchExactBooleanQueriesFrameByFrame) {
  const Scene scene = gallery("assembly_path.json");
  const auto fixture = MeshData::build(generatedMesh(scene.shapes[0]));
  const auto part = MeshData::build(generatedMesh(scene.shapes[1]));
  QuerySettings exact;
  exact.mode = QueryMode::Exact;
  QueryScratch scratch;
  for (Backend backend : {Backend::Exact, Backend::Adb, Backend::GImpact}) {
    SCOPED_TRACE(toString(backend));
    SceneWorld world(scene, backend);
    int agree = 0, sureDisagree = 0, overlapFrames = 0, begins = 0, ends = 0;
    bool was = false;
    for (int i = 0; i < scene.world.steps; ++i) {
      world.step();
      const bool truth = collide(fixture->tree, world.bodyPose(0), part->tree, world.bodyPose(1),
                                 exact, scratch)
                             .collides;
      const bool said = !world.overlapping().empty();
      const double confidence = said ? world.overlapping()[0].confidence : world.last().meanConfidence;
      agree += said == truth ? 1 : 0;
      sureDisagree += said != truth && confidence >= 0.99 ? 1 : 0;
      overlapFrames += truth ? 1 : 0;
      for (const OverlapEvent& e : world.events()) {
        EXPECT_EQ(e.begin, !was);  // begin and end alternate
        EXPECT_EQ(e.begin, said);
        was = e.begin;
        (e.begin ? begins : ends) += 1;
      }
    }
    EXPECT_GT(overlapFrames, 20);  // the off-centre push does hit
    EXPECT_LT(overlapFrames, scene.world.steps - 100);  // the centred one does not
    EXPECT_GE(begins, 1);
    EXPECT_EQ(begins, ends);
    std::printf("%s: %d of %d frames agree with exact queries\n", toString(backend), agree,
                scene.world.steps);
    if (backend == Backend::Exact) {
      EXPECT_EQ(agree, scene.world.steps);
    } else {
      if (backend == Backend::Adb) {
        EXPECT_EQ(sureDisagree, 0);
      }
      EXPECT_GE(agree, 0.97 * scene.world.steps);
    }
  }
}

const char* kBallAtWall = R"({
  "world": {"gravity": [0, 0, 0], "time_step": 0.016667, "steps": 30},
  "shapes": {"wall": {"type": "generated", "model": "box", "half_extents": [0.01, 1, 1]},
             "ball": {"type": "sphere", "radius": 0.1}},
  "bodies": [{"name": "wall", "shape": "wall", "kind": "static"},
             {"name": "ball", "shape": "ball", "position": [-2.5, 0, 0], "velocity": [60, 0, 0],
              "friction": 0.7, "restitution": 0.5}],
  "effects": EFFECTS
})";

Scene ballAtWall(const std::string& effects) {
  std::string text = kBallAtWall;
  text.replace(text.find("EFFECTS"), 7, effects);
  return parsed(text);
}

double ballX(Backend backend, const std::string& effects) {
  SceneWorld world(ballAtWall(effects), backend);
  for (int i = 0; i < 30; ++i) world.step();
  return world.bodyPose(1).translation.x();
}

TEST(SceneWorld, CcdStopsAFastBallAtAThinMeshWallAndWithoutItTheBallPassesThrough) {
  for (Backend backend : {Backend::Adb, Backend::GImpact}) {
    SCOPED_TRACE(toString(backend));
    EXPECT_LT(ballX(backend, R"(["dynamics", "ccd"])"), 0.0);
    EXPECT_GT(ballX(backend, R"(["dynamics"])"), 0.0);  // 1 m per step against 2 cm
  }
}

TEST(SceneWorld, EffectsLeftOutAreSwitchedOff) {
  SceneWorld plain(ballAtWall(R"(["dynamics"])"), Backend::Adb);
  SceneWorld full(ballAtWall(R"(["dynamics", "friction", "restitution", "sleeping"])"),
                  Backend::Adb);
  const btCollisionObject* ball = plain.dynamicsWorld()->getCollisionObjectArray()[1];
  EXPECT_EQ(ball->getFriction(), 0);
  EXPECT_EQ(ball->getRestitution(), 0);
  EXPECT_EQ(ball->getActivationState(), DISABLE_DEACTIVATION);
  const btCollisionObject* ball2 = full.dynamicsWorld()->getCollisionObjectArray()[1];
  EXPECT_FLOAT_EQ(ball2->getFriction(), 0.7f);
  EXPECT_FLOAT_EQ(ball2->getRestitution(), 0.5f);
  EXPECT_NE(ball2->getActivationState(), DISABLE_DEACTIVATION);
  EXPECT_FALSE(plain.built().ccd);
  EXPECT_FALSE(plain.built().sleeping);
  EXPECT_TRUE(full.built().sleeping);
}

TEST(SceneWorld, TheStackStaysStanding) {
  const Scene scene = gallery("stack.json");
  SceneWorld world(scene, Backend::Adb);
  const std::size_t top = world.bodyCount() - 1;
  const Vec3 start = world.bodyPose(top).translation;
  for (int i = 0; i < 240; ++i) world.step();  // 2 s
  EXPECT_LT((world.bodyPose(top).translation - start).norm(), 0.05);
  EXPECT_LT(world.last().kinetic, 0.05);
}

TEST(SceneWorld, TheDrivenGearTurnsTheFreeOne) {
  const Scene scene = gallery("gears_dynamics.json");
  SceneWorld world(scene, Backend::Adb);
  const double driver = scene.motions[0].angular.z();
  double turned = 0.0;
  Eigen::Quaterniond last(world.bodyPose(1).rotation);
  for (int i = 0; i < 240; ++i) {
    world.step();
    const Eigen::Quaterniond now(world.bodyPose(1).rotation);
    const Eigen::AngleAxisd step(now * last.inverse());  // world frame
    turned += step.angle() * (step.axis().z() < 0 ? -1.0 : 1.0);
    last = now;
  }
  // Same tooth count: the follower turns the other way at the driver's speed (within 15 %:
  // backlash and the first teeth's impact).
  const double seconds = 240 * scene.world.timeStep;
  EXPECT_NEAR(turned / seconds, -driver, 0.15 * driver);
}

TEST(SceneWorld, TheRecorderWritesStepsEventsAndASummary) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("adb_recorder_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  Scene scene = gallery("assembly_path.json");
  SceneWorld world(scene, Backend::Adb);
  Recorder recorder(world, dir);
  std::uint64_t events = 0;
  for (int i = 0; i < scene.world.steps; ++i) {
    events += world.step().events;
    recorder.record(world);
  }
  const RunSummary& s = recorder.finish();
  EXPECT_EQ(s.events, events);
  std::ifstream steps(dir / "steps.csv");
  std::string line;
  int rows = -1;
  while (std::getline(steps, line)) ++rows;
  EXPECT_EQ(rows, scene.world.steps);
  std::ifstream eventsFile(dir / "events.jsonl");
  std::uint64_t eventLines = 0;
  while (std::getline(eventsFile, line)) {
    const auto e = nlohmann::json::parse(line);
    EXPECT_TRUE(e["event"] == "begin" || e["event"] == "end");
    EXPECT_EQ(e["body1"], "part");
    ++eventLines;
  }
  EXPECT_EQ(eventLines, events);
  std::ifstream summaryFile(dir / "summary.json");
  const auto summary = nlohmann::json::parse(summaryFile);
  EXPECT_EQ(summary["steps"], scene.world.steps);
  EXPECT_EQ(summary["backend"], "adb");
  EXPECT_EQ(summary["effects"], "overlap");
  std::filesystem::remove_all(dir);
}

// A user's mesh file, far from the origin in its own coordinates and in other units: scaled,
// recentred on its box, dropped on a box, it comes to rest on it where the scene put it.
TEST(SceneWorld, AMeshFileIsScaledRecentredAndComesToRestWhereTheScenePutIt) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("adb_meshfile_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  {
    const TriangleMesh torus = gen::makeTorus(350, 120, 32, 16);  // millimetres, off-centre
    std::ofstream obj(dir / "ring.obj");
    for (const Vec3& v : torus.vertices()) obj << "v " << v.x() + 5000 << ' ' << v.y() << ' ' << v.z() << '\n';
    for (const Triangle& t : torus.triangles()) obj << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  }
  const Scene scene = parseScene(R"({
      "world": {"steps": 120},
      "shapes": {"floor": {"type": "box", "half_extents": [2, 0.25, 2]},
                 "ring": {"type": "mesh", "file": "ring.obj", "scale": 0.001}},
      "bodies": [{"name": "floor", "shape": "floor", "kind": "static", "position": [0, -0.25, 0]},
                 {"name": "ring", "shape": "ring", "position": [0.5, 0.5, 0],
                  "axis_angle": {"axis": [1, 0, 0], "degrees": 90}}],
      "effects": ["dynamics", "friction"]})",
                                 "meshfile.json", dir);
  for (Backend backend : {Backend::Adb, Backend::GImpact}) {
    SCOPED_TRACE(toString(backend));
    SceneWorld world(scene, backend);
    EXPECT_EQ(world.built().triangles, 32u * 16u * 2u);
    EXPECT_NEAR(world.scenePose(1).translation.x(), 0.5, 1e-9);
    for (int i = 0; i < 120; ++i) world.step();
    const Vec3 at = world.scenePose(1).translation;
    // Lying flat on the floor: its centre a tube's radius (0.12) above it, still near x = 0.5.
    EXPECT_NEAR(at.y(), 0.12, 0.02);
    EXPECT_NEAR(at.x(), 0.5, 0.05);
    EXPECT_LT(world.last().kinetic, 1e-3);
  }
  std::filesystem::remove_all(dir);
}

TEST(SceneWorld, AnUnreadableMeshFileIsNamedByItsShape) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("adb_badmesh_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "broken.obj") << "v 0 0 0\nv 1 0 0\nf 1 2 7\n";
  const Scene scene = parseScene(R"({"shapes": {"part": {"type": "mesh", "file": "broken.obj"}},
      "bodies": [{"shape": "part", "kind": "static"}], "effects": ["overlap"]})",
                                 "bad.json", dir);
  try {
    SceneWorld world(scene, Backend::Adb);
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.where(), "shapes.part.file");
    EXPECT_NE(std::string(e.what()).find("broken.obj"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace adb::scene
