// Tests of the generated test geometry (adb::gen): documented triangle counts, closedness and
// consistent outward winding, volumes against analytic values, no degenerate triangles, the
// named models' target counts and the merge/transform helpers.
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

// ---------------------------------------------------------------------------------------------
// Helpers

std::uint64_t edgeKey(std::uint32_t from, std::uint32_t to) {
  return (static_cast<std::uint64_t>(from) << 32) | to;
}

std::unordered_map<std::uint64_t, int> directedEdgeUses(const TriangleMesh& mesh) {
  std::unordered_map<std::uint64_t, int> uses;
  uses.reserve(3 * mesh.triangleCount());
  for (const Triangle& t : mesh.triangles()) {
    for (int k = 0; k < 3; ++k) ++uses[edgeKey(t[k], t[(k + 1) % 3])];
  }
  return uses;
}

// Closed and consistently wound: every directed edge is used once and its reverse once, so
// every undirected edge has exactly two triangles, which traverse it in opposite directions.
::testing::AssertionResult isClosedAndConsistent(const TriangleMesh& mesh) {
  const auto uses = directedEdgeUses(mesh);
  for (const auto& [key, count] : uses) {
    const auto from = static_cast<std::uint32_t>(key >> 32);
    const auto to = static_cast<std::uint32_t>(key & 0xffffffffu);
    const auto reverse = uses.find(edgeKey(to, from));
    if (count != 1 || reverse == uses.end() || reverse->second != 1) {
      return ::testing::AssertionFailure()
             << mesh.name() << ": edge " << from << "->" << to << " used " << count
             << " times, reverse " << (reverse == uses.end() ? 0 : reverse->second) << " times";
    }
  }
  return ::testing::AssertionSuccess();
}

// Divergence theorem: the sum of signed tetrahedra (origin, a, b, c); positive when outward.
double signedVolume(const TriangleMesh& mesh) {
  double sixTimes = 0.0;
  for (const Triangle& t : mesh.triangles()) {
    const Vec3 &a = mesh.vertices()[t[0]], &b = mesh.vertices()[t[1]], &c = mesh.vertices()[t[2]];
    sixTimes += a.dot(b.cross(c));
  }
  return sixTimes / 6.0;
}

double relativeError(double value, double expected) {
  return std::abs(value - expected) / std::abs(expected);
}

// Centre line of the torus knot as documented in mesh_generators.h; its length by dense sampling.
double torusKnotLength(int p, int q, double radius) {
  const auto at = [&](double t) {
    const double rho = radius + 0.5 * radius * std::cos(q * t);
    return Vec3(rho * std::cos(p * t), rho * std::sin(p * t), 0.5 * radius * std::sin(q * t));
  };
  constexpr int kSamples = 100000;
  double length = 0.0;
  for (int i = 0; i < kSamples; ++i) {
    length += (at(2 * kPi * (i + 1) / kSamples) - at(2 * kPi * i / kSamples)).norm();
  }
  return length;
}

// ---------------------------------------------------------------------------------------------
// Box

TEST(MeshGeneratorsTriangleCount, BoxIs12TimesSubdivisionsSquared) {
  for (int n : {1, 2, 5}) {
    const TriangleMesh box = gen::makeBox(Vec3(1, 2, 3), n);
    EXPECT_EQ(box.triangleCount(), static_cast<std::size_t>(12 * n * n)) << n;
    EXPECT_EQ(box.vertices().size(), static_cast<std::size_t>(6 * n * n + 2)) << n;
  }
}

TEST(MeshGeneratorsClosed, BoxIsClosedWithExactVolumeAndBounds) {
  const TriangleMesh box = gen::makeBox(Vec3(0.5, 0.25, 1.5), 4);
  EXPECT_TRUE(isClosedAndConsistent(box));
  EXPECT_NEAR(signedVolume(box), 8 * 0.5 * 0.25 * 1.5, 1e-12);
  EXPECT_EQ(box.bounds().lo, Vec3(-0.5, -0.25, -1.5));
  EXPECT_EQ(box.bounds().hi, Vec3(0.5, 0.25, 1.5));
}

// ---------------------------------------------------------------------------------------------
// Flat grid

TEST(MeshGeneratorsTriangleCount, FlatGridIs2NxNy) {
  const TriangleMesh grid = gen::makeFlatGrid(2.0, 1.0, 7, 3);
  EXPECT_EQ(grid.triangleCount(), 2u * 7 * 3);
  EXPECT_EQ(grid.vertices().size(), 8u * 4);
}

TEST(MeshGeneratorsFlat, FlatGridHasZeroThicknessAndFacesUp) {
  const TriangleMesh grid = gen::makeFlatGrid(2.0, 1.0, 7, 3);
  EXPECT_EQ(grid.bounds().extent().z(), 0.0);
  EXPECT_NEAR(grid.bounds().extent().x(), 2.0, 1e-15);
  EXPECT_NEAR(grid.bounds().extent().y(), 1.0, 1e-15);
  EXPECT_NEAR(grid.bounds().center().norm(), 0.0, 1e-15);
  for (const Triangle& t : grid.triangles()) {
    const Vec3 &a = grid.vertices()[t[0]], &b = grid.vertices()[t[1]], &c = grid.vertices()[t[2]];
    EXPECT_GT((b - a).cross(c - a).z(), 0.0);
  }
}

TEST(MeshGeneratorsFlat, FlatGridIsOpenWithBoundaryOnlyOnTheRim) {
  const TriangleMesh grid = gen::makeFlatGrid(1.0, 1.0, 5, 4);
  const auto uses = directedEdgeUses(grid);
  std::size_t boundary = 0;
  for (const auto& [key, count] : uses) {
    EXPECT_EQ(count, 1);
    const auto from = static_cast<std::uint32_t>(key >> 32);
    const auto to = static_cast<std::uint32_t>(key & 0xffffffffu);
    if (uses.count(edgeKey(to, from)) == 0) ++boundary;
  }
  EXPECT_EQ(boundary, 2u * (5 + 4));
}

// ---------------------------------------------------------------------------------------------
// Sphere, torus, cylinder

TEST(MeshGeneratorsTriangleCount, SphereIs20TimesSubdivisionsSquared) {
  for (int n : {1, 2, 3, 7}) {
    const TriangleMesh sphere = gen::makeSphere(1.0, n);
    EXPECT_EQ(sphere.triangleCount(), static_cast<std::size_t>(20 * n * n)) << n;
    EXPECT_EQ(sphere.vertices().size(), static_cast<std::size_t>(10 * n * n + 2)) << n;
  }
}

TEST(MeshGeneratorsClosed, SphereIsClosedOnTheSphereWithVolumeWithin2Percent) {
  const double r = 0.8;
  const TriangleMesh sphere = gen::makeSphere(r, 8);  // 1280 triangles
  EXPECT_TRUE(isClosedAndConsistent(sphere));
  for (const Vec3& v : sphere.vertices()) EXPECT_NEAR(v.norm(), r, 1e-12);
  // An inscribed polyhedron: slightly smaller than the ball.
  const double ball = 4.0 / 3.0 * kPi * r * r * r;
  EXPECT_LT(signedVolume(sphere), ball);
  EXPECT_LT(relativeError(signedVolume(sphere), ball), 0.02);
}

TEST(MeshGeneratorsTriangleCount, TorusIs2MajorMinor) {
  EXPECT_EQ(gen::makeTorus(1.0, 0.3, 12, 5).triangleCount(), 2u * 12 * 5);
}

TEST(MeshGeneratorsClosed, TorusIsClosedWithVolumeWithin2Percent) {
  const double big = 0.6, small = 0.25;
  const TriangleMesh torus = gen::makeTorus(big, small, 48, 24);
  EXPECT_TRUE(isClosedAndConsistent(torus));
  EXPECT_LT(relativeError(signedVolume(torus), 2 * kPi * kPi * big * small * small), 0.02);
}

TEST(MeshGeneratorsTriangleCount, CylinderFormula) {
  // 2 * segments * (heightSegments + 2 * capRings - 1)
  EXPECT_EQ(gen::makeCylinder(0.5, 1.0, 10).triangleCount(), 2u * 10 * (1 + 2 - 1));
  EXPECT_EQ(gen::makeCylinder(0.5, 1.0, 10, 3, 2).triangleCount(), 2u * 10 * (3 + 4 - 1));
}

TEST(MeshGeneratorsClosed, CylinderIsClosedWithTheExactPrismVolume) {
  const double r = 0.3, h = 0.7;
  const int m = 16;
  const TriangleMesh cylinder = gen::makeCylinder(r, h, m, 4, 3);
  EXPECT_TRUE(isClosedAndConsistent(cylinder));
  EXPECT_NEAR(signedVolume(cylinder), 0.5 * m * r * r * std::sin(2 * kPi / m) * h, 1e-12);
  EXPECT_NEAR(cylinder.bounds().extent().z(), h, 1e-15);
}

// ---------------------------------------------------------------------------------------------
// Torus knot

TEST(MeshGeneratorsTriangleCount, TorusKnotIs2SegmentsTubeSegments) {
  EXPECT_EQ(gen::makeTorusKnot(2, 3, 0.5, 0.07, 100, 9).triangleCount(), 2u * 100 * 9);
}

TEST(MeshGeneratorsClosed, TorusKnotIsClosedWithTubeVolumeWithin3Percent) {
  const double radius = 0.55, tube = 0.09;
  const TriangleMesh knot = gen::makeTorusKnot(2, 3, radius, tube, 400, 24);
  EXPECT_TRUE(isClosedAndConsistent(knot));
  // A tube that does not overlap itself has volume pi r^2 * (centre-line length).
  const double expected = kPi * tube * tube * torusKnotLength(2, 3, radius);
  EXPECT_LT(relativeError(signedVolume(knot), expected), 0.03);
}

TEST(MeshGeneratorsParameters, TorusKnotNeedsCoprimePQ) {
  EXPECT_THROW(gen::makeTorusKnot(2, 4, 0.5, 0.05, 100, 8), MeshError);
  EXPECT_NO_THROW(gen::makeTorusKnot(3, 2, 0.5, 0.05, 100, 8));
}

// ---------------------------------------------------------------------------------------------
// Gears

TEST(MeshGeneratorsTriangleCount, GearFormula) {
  // 4 * teeth * segmentsPerTooth * (radialSegments + axialSegments)
  EXPECT_EQ(gen::makeGear(10, 0.5, 0.4, 0.1, 0.2, 6).triangleCount(), 4u * 10 * 6 * 2);
  EXPECT_EQ(gen::makeGear(10, 0.5, 0.4, 0.1, 0.2, 5, 2, 3).triangleCount(), 4u * 10 * 5 * 5);
  EXPECT_EQ(gen::makeGearPair(10, 0.5, 0.4, 0.1, 0.2, 5, 2, 3).triangleCount(),
            2u * 4 * 10 * 5 * 5);
}

TEST(MeshGeneratorsClosed, GearIsClosedWithVolumeBetweenRootAndTipDiscs) {
  const double ro = 0.5, rr = 0.4, rb = 0.15, h = 0.25;
  const TriangleMesh gear = gen::makeGear(12, ro, rr, rb, h, 16, 2, 2);
  EXPECT_TRUE(isClosedAndConsistent(gear));
  // Teeth cover 25 % (tip) to 55 % (root) of the ring between the root and tip circles; 2 %
  // slack for the polygonal root circle.
  const double core = kPi * (rr * rr - rb * rb) * h, ring = kPi * (ro * ro - rr * rr) * h;
  EXPECT_GT(signedVolume(gear), 0.98 * (core + 0.25 * ring));
  EXPECT_LT(signedVolume(gear), core + 0.55 * ring);
  EXPECT_NEAR(gear.bounds().extent().z(), h, 1e-15);
}

// 2-D distance between segments ab and cd (0 when they cross).
double segmentDistance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                       const Eigen::Vector2d& d) {
  const auto cross = [](const Eigen::Vector2d& u, const Eigen::Vector2d& v) {
    return u.x() * v.y() - u.y() * v.x();
  };
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  if (d1 * d2 < 0 && d3 * d4 < 0) return 0.0;
  const auto pointToSegment = [](const Eigen::Vector2d& p, const Eigen::Vector2d& s,
                                 const Eigen::Vector2d& e) {
    const double t = std::clamp((p - s).dot(e - s) / (e - s).squaredNorm(), 0.0, 1.0);
    return (s + t * (e - s) - p).norm();
  };
  return std::min({pointToSegment(a, c, d), pointToSegment(b, c, d), pointToSegment(c, a, b),
                   pointToSegment(d, a, b)});
}

using Segments2 = std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>>;

// Edges of the top faces (z = thickness/2) of the two gears of a pair, left gear first, that
// reach into the strip |x| <= halfWidth between the gears. As the gears are extrusions of the
// same height, they overlap exactly when their top faces do.
std::array<Segments2, 2> topFaceEdges(const TriangleMesh& pair, double thickness,
                                      double halfWidth) {
  std::array<Segments2, 2> edges;
  const std::size_t half = pair.triangleCount() / 2;
  for (std::size_t i = 0; i < pair.triangleCount(); ++i) {
    const Triangle& t = pair.triangles()[i];
    for (int k = 0; k < 3; ++k) {
      const Vec3 &a = pair.vertices()[t[k]], &b = pair.vertices()[t[(k + 1) % 3]];
      const bool top = a.z() > 0.5 * thickness - 1e-9 && b.z() > 0.5 * thickness - 1e-9;
      const bool inStrip =
          std::min(a.x(), b.x()) <= halfWidth && std::max(a.x(), b.x()) >= -halfWidth;
      if (top && inStrip) {
        edges[i < half ? 0 : 1].emplace_back(a.head<2>(), b.head<2>());
      }
    }
  }
  return edges;
}

TEST(MeshGeneratorsGearPair, TeethInterleaveWithoutTouching) {
  const double ro = 0.5, rr = 0.4, h = 0.25;
  for (int teeth : {8, 12, 30}) {
    const TriangleMesh pair = gen::makeGearPair(teeth, ro, rr, 0.15, h, 8);
    EXPECT_TRUE(isClosedAndConsistent(pair));
    // The tip circles overlap in |x| <= 0.35 (ro - rr); the strip adds the gap we ask for.
    const auto edges = topFaceEdges(pair, h, ro - rr);
    double gap = 1e9;
    for (const auto& [a, b] : edges[0]) {
      for (const auto& [c, d] : edges[1]) gap = std::min(gap, segmentDistance(a, b, c, d));
    }
    EXPECT_GT(gap, 0.05 * (ro - rr)) << teeth << " teeth";
    // Interleaving: the left gear's tooth on the line of centres reaches past half the right
    // gear's tooth height, and the right gear's teeth beside it enter the left tip circle.
    const double distance = ro + rr + 0.3 * (ro - rr);
    const std::size_t split = pair.vertices().size() / 2;
    const auto deepest = [&](std::size_t begin, std::size_t end, const Vec3& centre) {
      double d = 1e9;
      for (std::size_t v = begin; v < end; ++v) {
        d = std::min(d, (pair.vertices()[v] - centre).head<2>().norm());
      }
      return d;
    };
    EXPECT_LT(deepest(0, split, Vec3(0.5 * distance, 0, 0)), rr + 0.5 * (ro - rr)) << teeth;
    EXPECT_LT(deepest(split, 2 * split, Vec3(-0.5 * distance, 0, 0)), ro) << teeth;
  }
}

// ---------------------------------------------------------------------------------------------
// Pipes and lock

TEST(MeshGeneratorsTriangleCount, PipeBundleFormula) {
  // 4 * pipes * segments * (lengthSegments + 1)
  EXPECT_EQ(gen::makePipeBundle(3, 1.0, 0.1, 0.02, 10, 6).triangleCount(), 4u * 3 * 10 * 7);
}

TEST(MeshGeneratorsClosed, PipeBundleIsClosedWithAnnulusVolumeWithin2Percent) {
  const int pipes = 5;
  const double length = 1.6, r = 0.08, wall = 0.02;
  const TriangleMesh bundle = gen::makePipeBundle(pipes, length, r, wall, 32, 40);
  EXPECT_TRUE(isClosedAndConsistent(bundle));
  // Pappus: annulus area times the length of the path of its centroid (the centre line).
  const double expected = pipes * kPi * (r * r - (r - wall) * (r - wall)) * length;
  EXPECT_LT(relativeError(signedVolume(bundle), expected), 0.02);
  // Concave and hollow: the material fills a small part of its bounding box.
  const Vec3 extent = bundle.bounds().extent();
  EXPECT_LT(signedVolume(bundle), 0.05 * extent.prod());
}

TEST(MeshGeneratorsClosed, LockAssemblyPartsAreClosedAndOutward) {
  const TriangleMesh lock = gen::makeLockAssembly(10);
  EXPECT_TRUE(isClosedAndConsistent(lock));
  // Parts overlap, so the divergence sum counts shared space twice: only its sign is checked
  // here, plus the size stated in the header.
  EXPECT_GT(signedVolume(lock), 0.3);  // the housing plate alone is 1.5 x 1.0 x 0.2
  const Vec3 extent = lock.bounds().extent();
  EXPECT_NEAR(extent.x(), 1.75, 0.05);
  EXPECT_NEAR(extent.y(), 1.0, 0.05);
  EXPECT_NEAR(extent.z(), 0.36, 0.05);
}

// ---------------------------------------------------------------------------------------------
// Named models

TEST(MeshGeneratorsModels, NamesAreTheDocumentedSix) {
  EXPECT_EQ(gen::modelNames(),
            (std::vector<std::string>{"pipes", "gears", "lock", "knot", "torus", "sphere"}));
}

TEST(MeshGeneratorsModels, HitTargetWithin25Percent) {
  for (const std::string& name : gen::modelNames()) {
    for (std::size_t target : {1000u, 10000u, 100000u}) {
      const TriangleMesh mesh = gen::makeModel(name, target);
      EXPECT_LT(
          relativeError(static_cast<double>(mesh.triangleCount()), static_cast<double>(target)),
          0.25)
          << name << " at " << target << ": " << mesh.triangleCount();
      EXPECT_EQ(mesh.name(), name);
    }
  }
}

TEST(MeshGeneratorsModels, CheapModelHitsAMillionWithin25Percent) {
  // The cheapest model only, to keep the file fast (the others were checked once by hand).
  const TriangleMesh mesh = gen::makeModel("torus", 1000000);
  EXPECT_LT(relativeError(static_cast<double>(mesh.triangleCount()), 1e6), 0.25);
}

TEST(MeshGeneratorsModels, AreClosedNonDegenerateAndAboutTwoUnitsAroundTheOrigin) {
  for (const std::string& name : gen::modelNames()) {
    const TriangleMesh mesh = gen::makeModel(name, 5000);
    EXPECT_TRUE(isClosedAndConsistent(mesh));
    EXPECT_GT(signedVolume(mesh), 0.0) << name;
    EXPECT_EQ(mesh.report().degenerateTriangles, 0u) << name;
    EXPECT_EQ(mesh.report().unusedVertices, 0u) << name;
    const Aabb& box = mesh.bounds();
    EXPECT_LE(box.lo.minCoeff(), -0.3) << name;
    EXPECT_GE(box.hi.maxCoeff(), 0.3) << name;
    EXPECT_GE(box.extent().maxCoeff(), 1.0) << name;
    EXPECT_LE(box.extent().maxCoeff(), 2.0) << name;
    EXPECT_LT(box.center().norm(), 0.2) << name;
  }
}

TEST(MeshGeneratorsDegenerate, NoGeneratorEmitsDegenerateTriangles) {
  const std::vector<TriangleMesh> meshes = {
      gen::makeBox(Vec3(1, 0.01, 2), 6),
      gen::makeFlatGrid(3.0, 0.5, 40, 5),
      gen::makeSphere(1.0, 1),
      gen::makeSphere(0.5, 40),
      gen::makeTorus(1.0, 0.1, 64, 6),
      gen::makeCylinder(0.05, 2.0, 64, 1, 8),
      gen::makeTorusKnot(3, 2, 0.5, 0.08, 300, 12),
      gen::makeGear(40, 0.5, 0.45, 0.1, 0.05, 4, 3, 1),
      gen::makePipeBundle(4, 0.5, 0.1, 0.005, 48, 3),
      gen::makeLockAssembly(1),
      gen::makeLockAssembly(60),
      gen::makeModel("gears", 200000),
  };
  for (const TriangleMesh& mesh : meshes) {
    EXPECT_EQ(mesh.report().degenerateTriangles, 0u) << mesh.name();
  }
}

TEST(MeshGeneratorsModels, UnknownNameThrowsListingTheKnownNames) {
  try {
    gen::makeModel("teapot", 1000);
    FAIL() << "expected MeshError";
  } catch (const MeshError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("teapot"), std::string::npos) << what;
    for (const std::string& name : gen::modelNames()) {
      EXPECT_NE(what.find(name), std::string::npos) << what;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Parameters, merge, transform

TEST(MeshGeneratorsParameters, InvalidParametersThrowMeshError) {
  EXPECT_THROW(gen::makeBox(Vec3(1, 0, 1)), MeshError);
  EXPECT_THROW(gen::makeBox(Vec3(1, 1, 1), 0), MeshError);
  EXPECT_THROW(gen::makeFlatGrid(1.0, 1.0, 0, 3), MeshError);
  EXPECT_THROW(gen::makeSphere(-1.0, 3), MeshError);
  EXPECT_THROW(gen::makeSphere(1.0, 100000), MeshError);  // too many triangles, not a bad_alloc
  EXPECT_THROW(gen::makeTorus(0.2, 0.3, 10, 10), MeshError);
  EXPECT_THROW(gen::makeCylinder(1.0, std::nan(""), 10), MeshError);
  EXPECT_THROW(gen::makeTorusKnot(2, 3, 0.5, 0.3, 100, 8), MeshError);
  EXPECT_THROW(gen::makeGear(12, 0.5, 0.6, 0.1, 0.2, 8), MeshError);
  EXPECT_THROW(gen::makeGear(12, 0.5, 0.4, 0.1, 0.2, 3), MeshError);
  EXPECT_THROW(gen::makePipeBundle(3, 1.0, 0.1, 0.1, 10, 4), MeshError);
  EXPECT_THROW(gen::makeLockAssembly(0), MeshError);
  EXPECT_THROW(gen::merge({}), MeshError);
}

TEST(MeshGeneratorsHelpers, MergeConcatenatesAndOffsetsIndices) {
  const TriangleMesh a = gen::makeBox(Vec3(1, 1, 1));
  const TriangleMesh b = gen::makeSphere(0.5, 2);
  const TriangleMesh both = gen::merge({a, b}, "both");
  EXPECT_EQ(both.name(), "both");
  EXPECT_EQ(both.triangleCount(), a.triangleCount() + b.triangleCount());
  EXPECT_EQ(both.vertices().size(), a.vertices().size() + b.vertices().size());
  const auto offset = static_cast<std::uint32_t>(a.vertices().size());
  EXPECT_EQ(both.triangles()[a.triangleCount()][0], b.triangles()[0][0] + offset);
  EXPECT_TRUE(isClosedAndConsistent(both));
  EXPECT_NEAR(signedVolume(both), signedVolume(a) + signedVolume(b), 1e-12);
}

TEST(MeshGeneratorsHelpers, TransformedMovesVerticesAndKeepsVolume) {
  const TriangleMesh torus = gen::makeTorus(0.6, 0.2, 24, 12);
  const Pose pose = Pose::fromQuaternion(
      Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized())), Vec3(5, -1, 2));
  const TriangleMesh moved = gen::transformed(torus, pose);
  EXPECT_EQ(moved.triangles(), torus.triangles());
  EXPECT_EQ(moved.name(), torus.name());
  for (std::size_t i = 0; i < torus.vertices().size(); ++i) {
    EXPECT_LT(
        (moved.vertices()[i] - (pose.rotation * torus.vertices()[i] + pose.translation)).norm(),
        1e-15);
  }
  EXPECT_NEAR(signedVolume(moved), signedVolume(torus), 1e-9);
  EXPECT_NEAR((moved.bounds().center() - pose.translation).norm(), 0.0, 0.05);
}

}  // namespace
}  // namespace adb
