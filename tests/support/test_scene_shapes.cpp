// Tests of the meshes shaped like real scenes' ones (plugin/support/src/scene_shapes.cpp and
// their names in model_catalogue.cpp): the sliver cylinder's documented count, closedness,
// outward winding and slivers at every target; the room's inward shell, its furniture inside
// it, its large flat and its thin triangles; the robot arm's size; the names and their errors;
// and the aspect ratio they are measured by. The benchmark models' own tests are in
// tests/core/test_mesh_generators.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "adb/support/mesh_generators.h"

namespace adb {
namespace {

constexpr double kPi = 3.14159265358979323846;

std::uint64_t edgeKey(std::uint32_t from, std::uint32_t to) {
  return (static_cast<std::uint64_t>(from) << 32) | to;
}

// Closed and consistently wound: every directed edge is used once and its reverse once.
::testing::AssertionResult isClosedAndConsistent(const TriangleMesh& mesh) {
  std::unordered_map<std::uint64_t, int> uses;
  for (const Triangle& t : mesh.triangles()) {
    for (int k = 0; k < 3; ++k) ++uses[edgeKey(t[k], t[(k + 1) % 3])];
  }
  for (const auto& [key, count] : uses) {
    const auto from = static_cast<std::uint32_t>(key >> 32);
    const auto to = static_cast<std::uint32_t>(key & 0xffffffffu);
    const auto reverse = uses.find(edgeKey(to, from));
    if (count != 1 || reverse == uses.end() || reverse->second != 1) {
      return ::testing::AssertionFailure() << mesh.name() << ": edge " << from << "->" << to
                                           << " used " << count << " times";
    }
  }
  return ::testing::AssertionSuccess();
}

// Divergence theorem: positive when the surface faces outward.
double signedVolume(const TriangleMesh& mesh) {
  double sixTimes = 0.0;
  for (const Triangle& t : mesh.triangles()) {
    sixTimes += mesh.vertices()[t[0]].dot(mesh.vertices()[t[1]].cross(mesh.vertices()[t[2]]));
  }
  return sixTimes / 6.0;
}

std::size_t countAspectAtLeast(const TriangleMesh& mesh, double aspect) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < mesh.triangleCount(); ++i) {
    n += gen::triangleAspect(mesh, i) >= aspect ? 1 : 0;
  }
  return n;
}

double relativeError(double value, double expected) {
  return std::abs(value - expected) / std::abs(expected);
}

// ---------------------------------------------------------------------------------------------
// Aspect ratio

TEST(SceneShapesAspect, IsLongestEdgeOverItsHeight) {
  const double s = std::sqrt(3.0) / 2.0;
  const TriangleMesh shapes({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, s, 0), Vec3(0, 0.01, 0),
                             Vec3(3, 0, 0)},
                            {{0, 1, 2}, {0, 4, 3}}, "aspects");
  EXPECT_NEAR(gen::triangleAspect(shapes, 0), 2.0 / std::sqrt(3.0), 1e-12);  // equilateral
  // A right triangle 3 long and 0.01 wide: longest^2 / (2 area) = (9 + 1e-4) / 0.03.
  EXPECT_NEAR(gen::triangleAspect(shapes, 1), (9.0 + 1e-4) / 0.03, 1e-9);
  EXPECT_NEAR(gen::medianAspect(shapes), (9.0 + 1e-4) / 0.03, 1e-9);  // the upper median of 2
}

// ---------------------------------------------------------------------------------------------
// Sliver cylinder

TEST(SceneShapesSliverCylinder, CountClosedOutwardAndInsideItsRadius) {
  for (const auto& [segments, rows] : {std::pair<int, int>{3, 1}, {12, 1}, {64, 1}, {200, 7}}) {
    const TriangleMesh mesh = gen::makeSliverCylinder(0.3, 2.0, segments, rows);
    EXPECT_EQ(mesh.triangleCount(), static_cast<std::size_t>(2 * segments * (rows + 1) - 4))
        << segments << "x" << rows;
    EXPECT_TRUE(isClosedAndConsistent(mesh));
    // Exactly the inscribed prism's volume: no centre vertex, nothing outside the rim.
    const double prism = 0.5 * segments * 0.09 * std::sin(2.0 * kPi / segments) * 2.0;
    EXPECT_NEAR(signedVolume(mesh), prism, 1e-12 * (1.0 + prism)) << segments << "x" << rows;
    EXPECT_EQ(mesh.report().degenerateTriangles, 0u);
    EXPECT_NEAR(mesh.bounds().hi.z(), 1.0, 1e-15);
    EXPECT_NEAR(mesh.bounds().lo.z(), -1.0, 1e-15);
    EXPECT_LE(mesh.bounds().hi.x(), 0.3 + 1e-15);
  }
}

TEST(SceneShapesSliverCylinder, SideAndCapTrianglesAreSlivers) {
  // 120 segments of a 0.25 radius: 1.309 % of the circumference each; 1 row of 1.8.
  const TriangleMesh mesh = gen::makeSliverCylinder(0.25, 1.8, 120, 1);
  const double side = 1.8 / (2.0 * kPi * 0.25 / 120.0);  // about 137.5
  std::size_t sides = 0, caps = 0;
  for (std::size_t i = 0; i < mesh.triangleCount(); ++i) {
    const double aspect = gen::triangleAspect(mesh, i);
    if (std::abs(aspect - side) < 0.01 * side) {
      ++sides;
    } else {
      // A cap fan from a rim vertex: at least about segments / pi.
      EXPECT_GE(aspect, 120.0 / kPi * 0.99) << "triangle " << i;
      ++caps;
    }
  }
  EXPECT_EQ(sides, 240u);
  EXPECT_EQ(caps, 2u * 118u);
}

TEST(SceneShapesSliverCylinder, InvalidParametersThrowMeshError) {
  EXPECT_THROW(gen::makeSliverCylinder(0.0, 1.0, 12), MeshError);
  EXPECT_THROW(gen::makeSliverCylinder(1.0, -1.0, 12), MeshError);
  EXPECT_THROW(gen::makeSliverCylinder(1.0, std::nan(""), 12), MeshError);
  EXPECT_THROW(gen::makeSliverCylinder(1.0, 1.0, 2), MeshError);
  EXPECT_THROW(gen::makeSliverCylinder(1.0, 1.0, 12, 0), MeshError);
  EXPECT_THROW(gen::makeSliverCylinder(1.0, 1.0, 1 << 30, 1 << 20), MeshError);  // too many
}

// "slivers" follows the target as the benchmark models do, its median triangle staying a
// sliver of about 100:1 (at least 20:1, the floor; FCL's env.obj: 125:1).
TEST(SceneShapesModels, SliversHitTargetWithSliversEverywhere) {
  for (std::size_t target : {1000u, 10000u, 100000u}) {
    const TriangleMesh mesh = gen::makeModel("slivers", target);
    EXPECT_EQ(mesh.name(), "slivers");
    EXPECT_LT(relativeError(static_cast<double>(mesh.triangleCount()), static_cast<double>(target)),
              0.25)
        << target << ": " << mesh.triangleCount();
    EXPECT_TRUE(isClosedAndConsistent(mesh)) << target;
    EXPECT_GT(signedVolume(mesh), 0.0) << target;
    EXPECT_EQ(mesh.report().degenerateTriangles, 0u) << target;
    EXPECT_GE(gen::medianAspect(mesh), 20.0) << target;
    EXPECT_GE(gen::medianAspect(mesh), 80.0) << target;
    EXPECT_LE(gen::medianAspect(mesh), 130.0) << target;
    // Every triangle is a sliver: the cap fans too.
    EXPECT_EQ(countAspectAtLeast(mesh, 20.0), mesh.triangleCount()) << target;
    EXPECT_NEAR(mesh.bounds().extent().z(), 1.8, 1e-12);
    // Centred but for the polygon's rim: an odd segment count leaves r (1 - cos(pi / s)).
    EXPECT_LT(mesh.bounds().center().norm(), 1e-4);
  }
}

TEST(SceneShapesModels, SliversHitAMillionWithin25Percent) {
  const TriangleMesh mesh = gen::makeModel("slivers", 1000000);
  EXPECT_LT(relativeError(static_cast<double>(mesh.triangleCount()), 1e6), 0.25);
  EXPECT_EQ(mesh.report().degenerateTriangles, 0u);
}

// ---------------------------------------------------------------------------------------------
// Room

TEST(SceneShapesRoom, ShellFacesInwardAroundFurnitureFacingOutward) {
  const TriangleMesh room = gen::makeRoom();
  EXPECT_EQ(room.triangleCount(), 1512u);  // documented in mesh_generators.h
  EXPECT_TRUE(isClosedAndConsistent(room));
  EXPECT_EQ(room.report().degenerateTriangles, 0u);
  EXPECT_EQ(room.report().unusedVertices, 0u);
  // 6 x 6 x 3, centred: the shell is the bounding box.
  EXPECT_LT((room.bounds().lo - Vec3(-3, -3, -1.5)).norm(), 1e-15);
  EXPECT_LT((room.bounds().hi - Vec3(3, 3, 1.5)).norm(), 1e-15);
  // The shell's first: eight corners, twelve triangles, its volume negative (inward).
  const TriangleMesh shell(
      std::vector<Vec3>(room.vertices().begin(), room.vertices().begin() + 8),
      std::vector<Triangle>(room.triangles().begin(), room.triangles().begin() + 12), "shell");
  EXPECT_TRUE(isClosedAndConsistent(shell));
  EXPECT_NEAR(signedVolume(shell), -108.0, 1e-9);
  // The furniture (everything after the shell) faces outward: it adds a positive volume,
  // and it stands inside the shell, at least 1 cm from every wall, the floor and the ceiling.
  const double furniture = signedVolume(room) - signedVolume(shell);
  EXPECT_GT(furniture, 0.5);
  EXPECT_LT(furniture, 5.0);
  for (std::size_t v = 8; v < room.vertices().size(); ++v) {
    const Vec3& p = room.vertices()[v];
    EXPECT_TRUE((p.cwiseAbs().array() <= Vec3(3, 3, 1.5).array() - 0.0099).all())
        << "vertex " << v << ": " << p.transpose();
  }
}

// Large flat triangles (the walls: 6 x 6 and 6 x 3 halves of rectangles) and many thin ones.
TEST(SceneShapesRoom, HasLargeFlatAndManyThinTriangles) {
  const TriangleMesh room = gen::makeRoom();
  for (std::size_t i = 0; i < 12; ++i) EXPECT_GE(room.triangleArea(i), 8.99) << "wall " << i;
  EXPECT_GE(gen::medianAspect(room), 20.0);
  EXPECT_GE(countAspectAtLeast(room, 20.0), room.triangleCount() * 6 / 10);
  EXPECT_GE(countAspectAtLeast(room, 100.0), 300u);
}

// ---------------------------------------------------------------------------------------------
// Robot arm

TEST(SceneShapesRobot, ALowPolyArmAboutAUnitLongAroundTheOrigin) {
  const TriangleMesh robot = gen::makeRobotArm();
  EXPECT_EQ(robot.triangleCount(), 296u);  // documented in mesh_generators.h
  EXPECT_EQ(robot.report().degenerateTriangles, 0u);
  EXPECT_EQ(robot.report().unusedVertices, 0u);
  // Every part is closed and outward (parts are not welded): so is their union by index.
  EXPECT_TRUE(isClosedAndConsistent(robot));
  EXPECT_GT(signedVolume(robot), 0.0);
  const Vec3 size = robot.bounds().extent();
  EXPECT_GE(size.maxCoeff(), 0.5);
  EXPECT_LE(size.maxCoeff(), 1.0);
  EXPECT_NEAR(size.x(), 0.8, 0.05);  // reaching along x
  EXPECT_NEAR(size.y(), 0.24, 0.01);  // the base's diameter
  EXPECT_NEAR(size.z(), 0.6, 0.05);
  EXPECT_LT(robot.bounds().center().norm(), 1e-12);
}

// ---------------------------------------------------------------------------------------------
// Names

TEST(SceneShapesModels, NamesAndTheirBuilders) {
  EXPECT_EQ(gen::realMeshModelNames(), (std::vector<std::string>{"slivers", "room", "robot"}));
  EXPECT_EQ(gen::fixedModelNames(), (std::vector<std::string>{"room", "robot"}));
  for (const std::string& name : gen::realMeshModelNames()) {
    const std::vector<std::string> benchmark = gen::modelNames();
    EXPECT_EQ(std::find(benchmark.begin(), benchmark.end(), name), benchmark.end()) << name;
  }
  const TriangleMesh room = gen::makeFixedModel("room");
  EXPECT_EQ(room.name(), "room");
  EXPECT_EQ(room.triangleCount(), gen::makeRoom().triangleCount());
  EXPECT_EQ(gen::makeFixedModel("robot").name(), "robot");
}

TEST(SceneShapesModels, WrongBuilderOrUnknownNameThrowsNamingTheKnownOnes) {
  try {
    gen::makeModel("room", 2000);
    FAIL() << "expected MeshError";
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("makeFixedModel"), std::string::npos) << e.what();
  }
  try {
    gen::makeFixedModel("slivers");
    FAIL() << "expected MeshError";
  } catch (const MeshError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("slivers"), std::string::npos) << what;
    EXPECT_NE(what.find("room, robot"), std::string::npos) << what;
  }
  try {
    gen::makeModel("chair", 1000);
    FAIL() << "expected MeshError";
  } catch (const MeshError& e) {
    EXPECT_NE(std::string(e.what()).find("slivers"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace adb
