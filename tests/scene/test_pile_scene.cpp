// The pile as scene data (makePileScene): every backend runs it, bodies start where the pile
// puts their centres of mass, files are sized to 0.8 across, a body out of the bin is lost,
// and the convex backend takes its shapes from the maker it is given.
#include <gtest/gtest.h>

#include <btBulletDynamicsCommon.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <unistd.h>

#include "adb/bullet/mesh_shape.h"
#include "adb/scene/pile_scene.h"
#include "adb/scene/scene_file.h"
#include "adb/scene/scene_world.h"
#include "adb/support/mesh_generators.h"

namespace adb::scene {
namespace {

namespace fs = std::filesystem;

PileSpec smallPile(PileSpec::Floor floor) {
  PileSpec spec;
  spec.bodies = 6;
  spec.trianglesPerBody = 400;
  spec.floor = floor;
  return spec;
}

TEST(PileScene, EveryFloorAndBackendRunsAndKeepsTheBodiesInTheBin) {
  for (PileSpec::Floor floor : {PileSpec::Floor::Mesh, PileSpec::Floor::Box, PileSpec::Floor::Plane}) {
    for (Backend backend : {Backend::Adb, Backend::Exact, Backend::GImpact}) {
      SCOPED_TRACE(std::to_string(static_cast<int>(floor)) + " " + toString(backend));
      SceneWorld world(makePileScene(smallPile(floor)), backend);
      EXPECT_EQ(world.bodyCount(), 5u + 6u);  // the bin's floor and four walls, the bodies
      EXPECT_EQ(world.built().meshBodies, floor == PileSpec::Floor::Mesh ? 11 : 6);
      for (int i = 0; i < 90; ++i) world.step();  // 1.5 s: the bodies fall 1 to 1.9 and land
      EXPECT_EQ(world.last().lost, 0);
      for (std::size_t b = 5; b < world.bodyCount(); ++b) {
        const Vec3 c = world.bodyPose(b).translation;
        EXPECT_GT(c.y(), -0.1);
        EXPECT_LT(c.y(), 1.0);  // landed: no body is still up at its start (1.0 and above)
        EXPECT_LT(c.cwiseAbs().x(), 2.5);
        EXPECT_LT(c.cwiseAbs().z(), 2.5);
      }
    }
  }
}

// world.threads runs the pair queries on threads; the simulation is the same to the bit.
TEST(PileScene, TheSameStepsOnOneAndTwoThreads) {
  PileSpec spec = smallPile(PileSpec::Floor::Mesh);
  spec.bodies = 12;
  std::vector<Vec3> where[2];
  for (int threads : {1, 2}) {
    Scene scene = makePileScene(spec);
    scene.world.threads = threads;
    SceneWorld world(scene, Backend::Adb);
    double parallelMicros = 0.0;
    std::uint64_t pairs = 0;
    for (int i = 0; i < 60; ++i) {
      world.step();
      parallelMicros += world.last().frame.parallelMicros;
      pairs += world.last().frame.pairs;
    }
    EXPECT_GT(pairs, 100u);  // mesh-mesh pairs met: the floor is a mesh
    EXPECT_EQ(world.last().frame.threads, static_cast<std::uint32_t>(threads));
    EXPECT_EQ(parallelMicros > 0.0, threads > 1);
    for (std::size_t b = 0; b < world.bodyCount(); ++b) {
      where[threads - 1].push_back(world.bodyPose(b).translation);
    }
  }
  ASSERT_EQ(where[0].size(), where[1].size());
  for (std::size_t b = 0; b < where[0].size(); ++b) {
    EXPECT_EQ(where[0][b], where[1][b]) << "body " << b;
  }
}

TEST(PileScene, ABodyStartsWithItsCentreOfMassWhereThePilePutsIt) {
  const Scene scene = makePileScene(smallPile(PileSpec::Floor::Box));
  SceneWorld world(scene, Backend::Adb);
  for (std::size_t b = 5; b < world.bodyCount(); ++b) {
    const BodySpec& spec = scene.bodies[b];
    ASSERT_EQ(spec.poseOf, BodySpec::PoseOf::CentreOfMass);
    // Bullet's body is its centre of mass: placed at the pose itself (to float rounding).
    EXPECT_LT((world.bodyPose(b).translation - spec.pose.translation).norm(), 1e-6);
    EXPECT_LT((world.bodyPose(b).rotation - spec.pose.rotation).norm(), 1e-6);
    EXPECT_LT((world.scenePose(b).translation - spec.pose.translation).norm(), 1e-6);
  }
  // The grid: 3 x 3 per layer 0.9 apart, jittered by at most 0.1, the first layer at 1.
  EXPECT_NEAR(scene.bodies[5].pose.translation.y(), 1.0, 1e-12);
  EXPECT_NEAR(scene.bodies[5].pose.translation.x(), -0.9, 0.1);
}

TEST(PileScene, AMeshFileIsSizedToItsLargestExtentWhateverItsUnits) {
  const fs::path dir = fs::temp_directory_path() / ("adb_pile_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  {
    const TriangleMesh torus = gen::makeTorus(350, 120, 24, 12);  // millimetres, off-centre
    std::ofstream obj(dir / "ring.obj");
    for (const Vec3& v : torus.vertices()) obj << "v " << v.x() + 5000 << ' ' << v.y() << ' ' << v.z() << '\n';
    for (const Triangle& t : torus.triangles()) obj << "f " << t[0] + 1 << ' ' << t[1] + 1 << ' ' << t[2] + 1 << '\n';
  }
  PileSpec spec = smallPile(PileSpec::Floor::Plane);
  spec.meshes = {dir / "ring.obj"};
  SceneWorld world(makePileScene(spec), Backend::Adb);
  EXPECT_EQ(world.built().triangles, 6u * 24u * 12u * 2u);
  EXPECT_NEAR(world.displayMesh(5).bounds().extent().maxCoeff(), 0.8, 1e-9);
  spec.meshes = {dir / "missing.obj"};
  EXPECT_THROW(SceneWorld(makePileScene(spec), Backend::Adb), SceneError);
  fs::remove_all(dir);
  spec.bodies = 0;
  EXPECT_THROW(makePileScene(spec), std::invalid_argument);
}

// Two balls, one over a floor and one beside it, with or without bounds over the floor.
Scene ballsBesideAFloor(bool bounds) {
  const std::string world =
      bounds ? R"("world": {"bounds": {"min": [-1, 0, -1], "max": [1, 5, 1]}},)" : "";
  return parseScene("{" + world + R"(
      "shapes": {"floor": {"type": "box", "half_extents": [1, 0.25, 1]},
                 "ball": {"type": "sphere", "radius": 0.1}},
      "bodies": [{"name": "floor", "shape": "floor", "kind": "static", "position": [0, -0.25, 0]},
                 {"name": "in", "shape": "ball", "position": [0, 0.5, 0]},
                 {"name": "out", "shape": "ball", "position": [1.5, 0.5, 0]}],
      "effects": ["dynamics"]})",
                    bounds ? "bounds.json" : "no_bounds.json");
}

// Steps `world` `steps` times; the first step after which a body was lost (0: none).
int firstStepLost(SceneWorld& world, int steps) {
  int first = 0;
  for (int step = 1; step <= steps; ++step) {
    if (world.step().lost > 0 && first == 0) first = step;
  }
  return first;
}

// A ball dropped beside a floor, with bounds over the floor: lost once its centre is below
// the bounds by more than a quarter of its size; a ball resting on the floor is not.
TEST(PileScene, ABodyOutOfTheBoundsByAQuarterOfItsSizeIsLost) {
  SceneWorld world(ballsBesideAFloor(true), Backend::Adb);
  const int firstLost = firstStepLost(world, 60);
  EXPECT_EQ(world.last().lost, 1);  // "out" fell beside the floor; "in" rests on it
  // Out on x from the start by 0.5, more than a quarter of the ball's box diagonal (0.087).
  EXPECT_EQ(firstLost, 1);
  EXPECT_NEAR(world.bodyPose(1).translation.y(), 0.1, 0.02);
}

// The same without bounds: a body whose centre falls below the lowest static body (the floor's
// bottom, y = -0.5) by more than its size (0.35) is lost; one resting on the floor is not.
TEST(PileScene, ABodyFallingPastTheFloorOfASceneWithoutBoundsIsLost) {
  SceneWorld world(ballsBesideAFloor(false), Backend::Adb);
  const int firstLost = firstStepLost(world, 60);
  EXPECT_EQ(world.last().lost, 1);
  // From y 0.5 to below -0.846: 1.35 m of free fall, 0.52 s, step 32 (Bullet's integration
  // takes a step or two more).
  EXPECT_GE(firstLost, 30);
  EXPECT_LE(firstLost, 36);
  EXPECT_NEAR(world.bodyPose(1).translation.y(), 0.1, 0.02);
}

// Bullet's deactivation, on by default in a pile: 27 gear pairs (800 triangles each) in three
// layers on a plane, with exact contacts, all asleep (measured: from step 542, the same pile
// as `adb-demo --model gears --bodies 27 --triangles 800 --floor plane --backend exact
// --steps 1400`, summary.json all_asleep_from) and still asleep after. Before contacts had identity and persisted, 50 such gears were awake at 600
// steps (issue 35).
TEST(PileScene, AGearPileOnAPlaneFallsAsleepWithExactContacts) {
  PileSpec spec;
  spec.bodies = 27;
  spec.model = "gears";
  spec.trianglesPerBody = 800;
  spec.floor = PileSpec::Floor::Plane;
  const Scene scene = makePileScene(spec);
  ASSERT_TRUE(scene.effects.sleeping);
  SceneWorld world(scene, Backend::Exact);
  int allAsleepFrom = 0;
  for (int step = 1; step <= 1400; ++step) {
    const StepRecord& r = world.step();
    ASSERT_EQ(r.lost, 0) << "step " << step;
    if (r.asleep == spec.bodies) {
      if (allAsleepFrom == 0) allAsleepFrom = step;
    } else {
      allAsleepFrom = 0;
    }
  }
  EXPECT_GT(allAsleepFrom, 0) << world.last().asleep << " of 27 asleep at the end";
  EXPECT_LE(allAsleepFrom, 1200);
}

TEST(PileScene, TheConvexBackendTakesItsShapesFromItsMakerOncePerMesh) {
  const Scene scene = makePileScene(smallPile(PileSpec::Floor::Box));
  EXPECT_THROW(SceneWorld(scene, Backend::Convex), std::invalid_argument);
  int made = 0;
  const ConvexShapeMaker boxes = [&made](const MeshData& mesh) {
    ++made;
    std::vector<std::unique_ptr<btCollisionShape>> shapes;
    const Vec3 half = 0.5 * mesh.mesh.bounds().extent();
    shapes.push_back(std::make_unique<btBoxShape>(
        btVector3(static_cast<btScalar>(half.x()), static_cast<btScalar>(half.y()),
                  static_cast<btScalar>(half.z()))));
    return shapes;
  };
  SceneWorld world(scene, Backend::Convex, boxes);
  EXPECT_EQ(made, 3);  // torus, gear, knot: shared by the six bodies
  const btCollisionObjectArray& objects = world.collisionWorld().getCollisionObjectArray();
  int boxBodies = 0;
  for (int i = 0; i < objects.size(); ++i) {
    boxBodies += objects[i]->getCollisionShape()->getShapeType() == BOX_SHAPE_PROXYTYPE &&
                 !objects[i]->isStaticObject();
  }
  EXPECT_EQ(boxBodies, 6);
  for (int i = 0; i < 60; ++i) world.step();
  EXPECT_EQ(world.last().lost, 0);
  EXPECT_EQ(parseBackend("convex"), Backend::Convex);
}

}  // namespace
}  // namespace adb::scene
