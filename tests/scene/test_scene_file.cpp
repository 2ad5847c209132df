// Scene files: a complete scene reads into the data it states; every kind of bad file gets
// one SceneError naming the file, the place (JSON path, or line and column) and the fault.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "adb/scene/scene_file.h"

namespace adb::scene {
namespace {

namespace fs = std::filesystem;

// A valid scene with every section; tests break one thing in it at a time.
const char* kScene = R"({
  "description": "a torus on a box, a kinematic pusher",
  "world": {"gravity": [0, -10, 0], "time_step": 0.01, "steps": 50, "substeps": 2,
            "budget": {"node_pairs": 20000}, "p_accept": 0.8},
  "shapes": {
    "ground": {"type": "box", "half_extents": [5, 0.5, 5]},
    "ring": {"type": "generated", "model": "torus", "triangles": 1000, "scale": 0.5},
    "ball": {"type": "sphere", "radius": 0.2},
    "floor": {"type": "plane", "normal": [0, 2, 0], "offset": -1}
  },
  "bodies": [
    {"name": "ground", "shape": "ground", "kind": "static", "position": [0, -0.5, 0]},
    {"name": "ring", "shape": "ring", "mass": 2, "position": [0, 1, 0],
     "axis_angle": {"axis": [1, 0, 0], "degrees": 90}, "friction": 0.3, "restitution": 0.1},
    {"name": "pusher", "shape": "ball", "kind": "kinematic", "quaternion": [1, 0, 0, 0]},
    {"name": "plane", "shape": "floor", "kind": "static"}
  ],
  "motions": [{"body": "pusher", "twist": {"linear": [1, 0, 0]}}],
  "effects": ["dynamics", "friction", "restitution"]
})";

// The error that parsing `text` throws (fails the test if none).
SceneError errorOf(const std::string& text, const fs::path& folder = {}) {
  try {
    parseScene(text, "scene.json", folder);
  } catch (const SceneError& e) {
    return e;
  }
  ADD_FAILURE() << "no SceneError for:\n" << text;
  return SceneError("", "", "");
}

// kScene with `from` replaced by `to` (which must occur).
std::string edited(const std::string& from, const std::string& to) {
  std::string s = kScene;
  const std::size_t at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

TEST(SceneFile, AValidSceneReadsIntoWhatItStates) {
  const Scene s = parseScene(kScene, "scene.json");
  EXPECT_EQ(s.description, "a torus on a box, a kinematic pusher");
  EXPECT_EQ(s.world.gravity, Vec3(0, -10, 0));
  EXPECT_DOUBLE_EQ(s.world.timeStep, 0.01);
  EXPECT_EQ(s.world.steps, 50);
  EXPECT_EQ(s.world.substeps, 2);
  EXPECT_EQ(s.world.budget.kind, BudgetSpec::Kind::NodePairs);
  EXPECT_EQ(s.world.budget.nodePairs, 20000u);
  EXPECT_DOUBLE_EQ(s.world.pAccept, 0.8);
  EXPECT_DOUBLE_EQ(s.world.pMin, 0.99);  // a default
  ASSERT_EQ(s.shapes.size(), 4u);
  ASSERT_EQ(s.bodies.size(), 4u);
  const BodySpec& ring = s.bodies[1];
  EXPECT_EQ(s.shapes[ring.shape].kind, ShapeSpec::Kind::Generated);
  EXPECT_EQ(s.shapes[ring.shape].model, "torus");
  EXPECT_EQ(s.shapes[ring.shape].triangles, 1000u);
  EXPECT_DOUBLE_EQ(ring.mass, 2.0);
  EXPECT_NEAR((ring.pose.rotation * Vec3::UnitY() - Vec3::UnitZ()).norm(), 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(ring.friction, 0.3);
  EXPECT_EQ(s.bodies[0].kind, BodySpec::Kind::Static);
  EXPECT_EQ(s.bodies[2].kind, BodySpec::Kind::Kinematic);
  const ShapeSpec& plane = s.shapes[s.bodies[3].shape];
  EXPECT_NEAR((plane.normal - Vec3::UnitY()).norm(), 0.0, 1e-15);  // normalised
  ASSERT_EQ(s.motions.size(), 1u);
  EXPECT_EQ(s.motions[0].body, 2u);
  EXPECT_EQ(s.motions[0].linear, Vec3(1, 0, 0));
  EXPECT_EQ(s.effects.kind, Effects::Kind::Dynamics);
  EXPECT_TRUE(s.effects.friction && s.effects.restitution);
  EXPECT_FALSE(s.effects.sleeping || s.effects.ccd || s.effects.softContacts);
}

TEST(SceneFile, ASyntaxErrorNamesItsLineAndColumn) {
  // Line 3 is "  "world": {"gravity": [0, -10, 0] "time_step"...": a comma missing.
  const SceneError e = errorOf(edited("[0, -10, 0], \"time_step\"", "[0, -10, 0] \"time_step\""));
  EXPECT_EQ(e.file(), "scene.json");
  EXPECT_EQ(e.where().rfind("line 3, column ", 0), 0u) << e.what();
  EXPECT_NE(std::string(e.what()).find("syntax error"), std::string::npos) << e.what();
}

TEST(SceneFile, AnUnknownKeyIsNeverIgnored) {
  const SceneError e = errorOf(edited("\"friction\": 0.3", "\"frction\": 0.3"));
  EXPECT_EQ(e.where(), "bodies[1].frction");
  EXPECT_NE(std::string(e.what()).find("unknown key 'frction'"), std::string::npos) << e.what();
  EXPECT_EQ(errorOf(edited("\"steps\": 50", "\"step\": 50")).where(), "world.step");
  EXPECT_EQ(errorOf(edited("\"description\"", "\"descripton\"")).where(), "descripton");
}

TEST(SceneFile, AWrongTypeIsNamed) {
  const SceneError e = errorOf(edited("\"mass\": 2", "\"mass\": \"2\""));
  EXPECT_EQ(e.where(), "bodies[1].mass");
  EXPECT_NE(std::string(e.what()).find("expected a number, got a string"), std::string::npos)
      << e.what();
  EXPECT_EQ(errorOf(edited("\"steps\": 50", "\"steps\": 50.5")).where(), "world.steps");
  EXPECT_EQ(errorOf(edited("[0, -0.5, 0]", "[0, -0.5]")).where(), "bodies[0].position");
  EXPECT_EQ(errorOf(edited("\"radius\": 0.2", "\"radius\": true")).where(), "shapes.ball.radius");
}

TEST(SceneFile, AMissingMeshFileIsNamedWithItsPath) {
  const fs::path folder = fs::temp_directory_path() / "adb_scene_test_missing";
  fs::create_directories(folder);
  const std::string scene = edited("{\"type\": \"sphere\", \"radius\": 0.2}",
                                   "{\"type\": \"mesh\", \"file\": \"nowhere/part.obj\"}");
  const SceneError e = errorOf(scene, folder);
  EXPECT_EQ(e.where(), "shapes.ball.file");
  EXPECT_NE(std::string(e.what()).find((folder / "nowhere/part.obj").string()), std::string::npos)
      << e.what();
  // The same file present: read (its contents are checked when the scene is built).
  fs::create_directories(folder / "nowhere");
  std::ofstream(folder / "nowhere/part.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const Scene read = parseScene(scene, "scene.json", folder);
  EXPECT_EQ(read.shapes[read.bodies[2].shape].file, folder / "nowhere/part.obj");
  EXPECT_EQ(read.shapes[2].name, "ball");  // shapes keep the file's order
  fs::remove_all(folder);
}

// What the pile needs of a scene, in a file: a mesh sized to its largest extent, a pose that
// places the centre of mass, and bounds out of which a body is lost.
TEST(SceneFile, SizeCentreOfMassPosesAndBoundsReadAndTheirFaultsAreNamed) {
  const fs::path folder = fs::temp_directory_path() / "adb_scene_test_size";
  fs::create_directories(folder);
  std::ofstream(folder / "part.obj") << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                        "f 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n";
  std::string text = edited("{\"type\": \"sphere\", \"radius\": 0.2}",
                            "{\"type\": \"mesh\", \"file\": \"part.obj\", \"size\": 0.8}");
  text = text.replace(text.find("\"mass\": 2,"), 10, "\"mass\": 2, \"pose_of\": \"centre_of_mass\",");
  text = text.replace(text.find("\"p_accept\""), 0,
                      "\"bounds\": {\"min\": [-1, 0, -1], \"max\": [1, 9, 1]}, ");
  const Scene s = parseScene(text, "scene.json", folder);
  EXPECT_DOUBLE_EQ(s.shapes[2].size, 0.8);
  EXPECT_EQ(s.bodies[1].poseOf, BodySpec::PoseOf::CentreOfMass);
  EXPECT_EQ(s.bodies[0].poseOf, BodySpec::PoseOf::Mesh);  // the default
  ASSERT_TRUE(s.world.bounds.has_value());
  EXPECT_EQ(s.world.bounds->lo, Vec3(-1, 0, -1));
  EXPECT_EQ(s.world.bounds->hi, Vec3(1, 9, 1));

  const auto faultOf = [&](const std::string& from, const std::string& to) {
    std::string bad = text;
    bad.replace(bad.find(from), from.size(), to);
    try {
      parseScene(bad, "scene.json", folder);
    } catch (const SceneError& e) {
      return std::string(e.what()).substr(std::string("scene.json: ").size());
    }
    return std::string("no error");
  };
  EXPECT_EQ(faultOf("\"size\": 0.8", "\"size\": 0.8, \"scale\": 2"),
            "shapes.ball.size: give either 'size' or 'scale' and 'recentre', not both");
  EXPECT_EQ(faultOf("\"size\": 0.8", "\"size\": -1").rfind("shapes.ball.size: ", 0), 0u);
  EXPECT_EQ(faultOf("\"centre_of_mass\"", "\"center\""),
            "bodies[1].pose_of: 'center' is not one of mesh, centre_of_mass");
  EXPECT_EQ(faultOf("\"kind\": \"static\", \"position\": [0, -0.5, 0]}",
                    "\"kind\": \"static\", \"position\": [0, -0.5, 0], \"pose_of\": \"centre_of_mass\"}"),
            "bodies[0].pose_of: only a dynamic mesh body has a centre of mass to place");
  EXPECT_EQ(faultOf("\"max\": [1, 9, 1]", "\"max\": [1, 0, 1]"),
            "world.bounds.max: must exceed 'min' on every axis");
  EXPECT_EQ(faultOf("\"max\": [1, 9, 1]", "\"top\": [1, 9, 1]").rfind("world.bounds", 0), 0u);
  fs::remove_all(folder);
}

TEST(SceneFile, UnknownShapesAndModelsListWhatIsKnown) {
  const SceneError body = errorOf(edited("\"shape\": \"ring\"", "\"shape\": \"rnig\""));
  EXPECT_EQ(body.where(), "bodies[1].shape");
  EXPECT_NE(std::string(body.what()).find("unknown shape 'rnig' (shapes: "), std::string::npos)
      << body.what();
  const SceneError type = errorOf(edited("\"type\": \"sphere\"", "\"type\": \"cone\""));
  EXPECT_EQ(type.where(), "shapes.ball.type");
  const SceneError model = errorOf(edited("\"model\": \"torus\"", "\"model\": \"tours\""));
  EXPECT_EQ(model.where(), "shapes.ring.model");
  EXPECT_NE(std::string(model.what()).find("torus"), std::string::npos) << model.what();
}

TEST(SceneFile, ANegativeOrZeroMassIsRefused) {
  for (const char* mass : {"-1", "0"}) {
    const SceneError e = errorOf(edited("\"mass\": 2", std::string("\"mass\": ") + mass));
    EXPECT_EQ(e.where(), "bodies[1].mass");
    EXPECT_NE(std::string(e.what()).find("must be positive"), std::string::npos) << e.what();
  }
  // A mass on a static body is a mistake, not a default.
  EXPECT_EQ(errorOf(edited("\"kind\": \"static\", \"position\"",
                           "\"kind\": \"static\", \"mass\": 1, \"position\""))
                .where(),
            "bodies[0].mass");
}

TEST(SceneFile, AnEffectThatNeedsAnotherIsRefused) {
  const SceneError e =
      errorOf(edited("[\"dynamics\", \"friction\", \"restitution\"]", "[\"contacts\", \"restitution\"]"));
  EXPECT_EQ(e.where(), "effects");
  EXPECT_NE(std::string(e.what()).find("'restitution' needs 'dynamics'"), std::string::npos)
      << e.what();
  EXPECT_EQ(errorOf(edited("[\"dynamics\", \"friction\", \"restitution\"]",
                           "[\"overlap\", \"dynamics\"]"))
                .where(),
            "effects");  // one kind of simulation
  EXPECT_EQ(errorOf(edited("\"restitution\"]", "\"bounce\"]")).where(), "effects[2]");
}

TEST(SceneFile, ReferencesAndMotionsAreChecked) {
  // A motion for a body that is not kinematic, or for no body.
  EXPECT_EQ(errorOf(edited("{\"body\": \"pusher\"", "{\"body\": \"ring\"")).where(),
            "motions[0].body");
  EXPECT_EQ(errorOf(edited("{\"body\": \"pusher\"", "{\"body\": \"nobody\"")).where(),
            "motions[0].body");
  // Two bodies of one name.
  EXPECT_EQ(errorOf(edited("{\"name\": \"pusher\"", "{\"name\": \"ring\"")).where(),
            "bodies[2].name");
  // Keyframes must go forward in time.
  const std::string keys =
      edited("\"twist\": {\"linear\": [1, 0, 0]}",
             "\"keyframes\": [{\"time\": 1, \"position\": [0, 0, 0]}, {\"time\": 0.5}]");
  EXPECT_EQ(errorOf(keys).where(), "motions[0].keyframes[1].time");
  // A zero quaternion or axis has no rotation.
  EXPECT_EQ(errorOf(edited("[1, 0, 0, 0]", "[0, 0, 0, 0]")).where(), "bodies[2].quaternion");
}

TEST(SceneFile, NonFiniteAndOutOfRangeNumbersAreRefused) {
  EXPECT_EQ(errorOf(edited("\"time_step\": 0.01", "\"time_step\": 0")).where(), "world.time_step");
  EXPECT_EQ(errorOf(edited("\"p_accept\": 0.8", "\"p_accept\": 1.5")).where(), "world.p_accept");
  const SceneError fronts =
      errorOf(edited("\"p_accept\": 0.8", "\"p_accept\": 0.8, \"fronts\": \"sometimes\""));
  EXPECT_EQ(fronts.where(), "world.fronts");
  EXPECT_NE(std::string(fronts.what()).find("not one of node_pair_budget, always, never"),
            std::string::npos)
      << fronts.what();
  EXPECT_EQ(errorOf(edited("\"p_accept\": 0.8", "\"p_accept\": 0.8, \"threads\": -1")).where(),
            "world.threads");
  EXPECT_EQ(errorOf(edited("\"p_accept\": 0.8", "\"p_accept\": 0.8, \"threads\": 1.5")).where(),
            "world.threads");
  EXPECT_EQ(parseScene(edited("\"p_accept\": 0.8", "\"p_accept\": 0.8, \"threads\": 2"),
                       "scene.json")
                .world.threads,
            2);
  EXPECT_EQ(errorOf(edited("[5, 0.5, 5]", "[5, -0.5, 5]")).where(), "shapes.ground.half_extents");
  EXPECT_EQ(errorOf(edited("\"node_pairs\": 20000", "\"node_pairs\": -3")).where(),
            "world.budget.node_pairs");
  // JSON has no NaN or infinity; a number beyond a double is refused as it is read.
  const SceneError huge = errorOf(edited("\"restitution\": 0.1", "\"restitution\": 1e999"));
  EXPECT_NE(std::string(huge.what()).find("number overflow parsing '1e999'"), std::string::npos)
      << huge.what();
}

TEST(SceneFile, LoadingNamesTheFileAndReadsMeshPathsBesideIt) {
  const fs::path folder = fs::temp_directory_path() / "adb_scene_test_load";
  fs::create_directories(folder);
  const fs::path file = folder / "pile.json";
  std::ofstream(file) << kScene;
  const Scene s = loadScene(file);
  EXPECT_EQ(s.file, file);
  EXPECT_EQ(s.bodies.size(), 4u);
  try {
    loadScene(folder / "absent.json");
    ADD_FAILURE() << "no error for a missing scene file";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.file(), (folder / "absent.json").string());
    EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos);
  }
  fs::remove_all(folder);
}

TEST(SceneFile, GarbageNeverCrashes) {
  // Truncations of a valid scene, and values of every type where objects are expected.
  const std::string scene = kScene;
  for (std::size_t n = 0; n < scene.size(); n += 7) {
    EXPECT_THROW(parseScene(scene.substr(0, n), "cut.json"), SceneError) << n;
  }
  for (const char* text : {"[]", "42", "null", "\"scene\"", "{\"shapes\": []}",
                           "{\"shapes\": {\"a\": 1}, \"bodies\": [], \"effects\": []}"}) {
    EXPECT_THROW(parseScene(text, "odd.json"), SceneError) << text;
  }
}

// What a damaged file wrote is quoted short and printable: the file can hold megabytes where
// a name or a number should be.
TEST(SceneFile, HugeNamesAndTokensAreQuotedShortAndPrintable) {
  const std::string huge(100000, 'k');
  const auto expectShort = [](const SceneError& e, const std::string& part) {
    const std::string what = e.what();
    EXPECT_LT(what.size(), 400u) << what.substr(0, 1000);
    EXPECT_LT(e.where().size(), 200u) << e.where().substr(0, 1000);
    EXPECT_NE(what.find(part), std::string::npos) << what.substr(0, 1000);
    for (const char c : what) EXPECT_GE(static_cast<unsigned char>(c), 0x20u) << what;
  };
  // A shape's name: in the JSON path of the error.
  expectShort(errorOf(edited("\"ball\": {\"type\": \"sphere\"", "\"" + huge + "\": {\"type\": \"spere\"")),
              "more bytes)");
  // An unknown key, a string with a control character, a number too large to hold.
  expectShort(errorOf(edited("\"friction\": 0.3", "\"" + huge + "\": 0.3")), "unknown key 'kkk");
  const SceneError control = errorOf(edited("\"torus\"", "\"" + huge + "\x01\""));
  expectShort(control, "control character");
  EXPECT_EQ(control.where().rfind("line ", 0), 0u) << control.where();
  expectShort(errorOf(edited("\"steps\": 50", "\"steps\": 1" + std::string(100000, '2'))), "overflow");
  // The list of known shapes names ten, then says how many more.
  std::string many = "\"shapes\": {";
  for (int i = 0; i < 30; ++i) many += "\"s" + std::to_string(i) + "\": {\"type\": \"sphere\", \"radius\": 1}, ";
  std::string text = edited("\"shapes\": {", many);
  const std::string ref = "\"shape\": \"ball\"";
  text.replace(text.find(ref), ref.size(), "\"shape\": \"bal\"");
  expectShort(errorOf(text), "and 24 more)");
}

}  // namespace
}  // namespace adb::scene
