// TriangleMesh: validation at construction (bad input gets one clear error) and reports.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "adb/core/mesh.h"

namespace adb {
namespace {

std::vector<Vec3> unitTriangleVertices() { return {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}; }

// Expects MeshError whose message contains every one of `parts`.
template <typename F>
void expectMeshError(F&& make, std::initializer_list<const char*> parts) {
  try {
    make();
    FAIL() << "expected MeshError";
  } catch (const MeshError& e) {
    for (const char* part : parts) EXPECT_NE(std::string(e.what()).find(part), std::string::npos)
        << "message '" << e.what() << "' lacks '" << part << "'";
  }
}

TEST(MeshBadInput, NaNCoordinateNamesTheVertex) {
  auto v = unitTriangleVertices();
  v[2].y() = std::numeric_limits<double>::quiet_NaN();
  expectMeshError([&] { TriangleMesh(v, {{0, 1, 2}}, "part.obj"); },
                  {"part.obj", "vertex 2", "non-finite"});
}

TEST(MeshBadInput, InfiniteCoordinateNamesTheVertex) {
  auto v = unitTriangleVertices();
  v[1].x() = -std::numeric_limits<double>::infinity();
  expectMeshError([&] { TriangleMesh(v, {{0, 1, 2}}); }, {"vertex 1", "non-finite"});
}

TEST(MeshBadInput, OutOfRangeIndexNamesTriangleAndVertex) {
  expectMeshError([&] { TriangleMesh(unitTriangleVertices(), {{0, 1, 2}, {0, 2, 7}}); },
                  {"triangle 1", "vertex 7", "3 vertices"});
}

TEST(MeshBadInput, EmptyMeshIsRejected) {
  expectMeshError([&] { TriangleMesh({}, {}); }, {"no triangles"});
  expectMeshError([&] { TriangleMesh(unitTriangleVertices(), {}); }, {"no triangles"});
}

TEST(MeshBadInput, ErrorIsAnInvalidArgument) {
  EXPECT_THROW(TriangleMesh({}, {}), std::invalid_argument);
}

TEST(MeshDegenerate, DegenerateTrianglesAreKeptAndCounted) {
  std::vector<Vec3> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}};
  // A good triangle, a repeated index, a collinear one, two distinct vertices at one place.
  v.push_back({1, 0, 0});
  TriangleMesh m(v, {{0, 1, 2}, {0, 0, 2}, {0, 1, 3}, {1, 4, 2}});
  EXPECT_EQ(m.triangleCount(), 4u);
  EXPECT_EQ(m.report().degenerateTriangles, 3u);
  EXPECT_EQ(m.report().repeatedVertexTriangles, 2u);
  EXPECT_DOUBLE_EQ(m.triangleArea(0), 0.5);
  EXPECT_DOUBLE_EQ(m.triangleArea(2), 0.0);
  EXPECT_FALSE(m.isDegenerate(0));
}

TEST(MeshReport, UnusedVerticesAreCountedAndLeftOutOfTheBounds) {
  auto v = unitTriangleVertices();
  v.push_back({100, 100, 100});
  TriangleMesh m(v, {{0, 1, 2}});
  EXPECT_EQ(m.report().unusedVertices, 1u);
  EXPECT_DOUBLE_EQ(m.bounds().hi.x(), 1.0);
}

}  // namespace
}  // namespace adb
