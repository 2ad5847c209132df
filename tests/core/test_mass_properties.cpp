// computeMassProperties: analytic solids (box, sphere, torus, cylinder), the thin-shell fallback
// for open or flat meshes, the point mass for zero area, winding/welding rules for `closed`,
// precision far from the origin and at extreme scales, and the principal frame's contract.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "adb/core/mass_properties.h"
#include "adb/support/mesh_generators.h"

namespace adb {
namespace {

constexpr double kPi = 3.14159265358979323846;

// |a - b| within `tol` of the larger magnitude.
::testing::AssertionResult relNear(double a, double b, double tol) {
  const double scale = std::max(std::abs(a), std::abs(b));
  if (std::abs(a - b) <= tol * scale) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " vs " << b << " (relative difference "
                                       << std::abs(a - b) / scale << ", allowed " << tol << ")";
}

// Frobenius distance within `tol` of the larger norm. Both are divided by the largest
// coefficient first so that tensors near 1e200 do not overflow the norm.
::testing::AssertionResult matNear(const Mat3& a, const Mat3& b, double tol) {
  const double unit = std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
  if (unit == 0.0) return ::testing::AssertionSuccess();
  const Mat3 as = a / unit, bs = b / unit;
  const double scale = std::max(as.norm(), bs.norm());
  if ((as - bs).norm() <= tol * scale) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "\n" << a << "\nvs\n" << b << "\n(relative difference "
                                       << (as - bs).norm() / scale << ", allowed " << tol << ")";
}

::testing::AssertionResult vecNear(const Vec3& a, const Vec3& b, double absTol) {
  if ((a - b).norm() <= absTol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a.transpose() << " vs " << b.transpose()
                                       << " (distance " << (a - b).norm() << ", allowed "
                                       << absTol << ")";
}

bool allFinite(const MassProperties& p) {
  return std::isfinite(p.volume) && std::isfinite(p.area) && p.centerOfMass.allFinite() &&
         p.inertia.allFinite() && p.principalAxes.allFinite() && p.principalMoments.allFinite();
}

// The principal frame's contract: rotation (orthonormal, det +1), moments >= 0 and ascending,
// and axes * diag(moments) * axes^T reproducing the tensor.
void expectValidFrame(const MassProperties& p) {
  ASSERT_TRUE(allFinite(p));
  const Mat3& a = p.principalAxes;
  EXPECT_TRUE((a.transpose() * a - Mat3::Identity()).norm() < 1e-12) << a;
  EXPECT_NEAR(a.determinant(), 1.0, 1e-12);
  EXPECT_GE(p.principalMoments[0], 0.0);
  EXPECT_LE(p.principalMoments[0], p.principalMoments[1]);
  EXPECT_LE(p.principalMoments[1], p.principalMoments[2]);
  const Mat3 rebuilt = a * p.principalMoments.asDiagonal() * a.transpose();
  EXPECT_TRUE(matNear(rebuilt, p.inertia, 1e-12));
  EXPECT_TRUE(p.inertia == p.inertia.transpose());  // exactly symmetric
}

// Solid box [-h, h]: unit-mass inertia diag((b^2 + c^2)/3, (a^2 + c^2)/3, (a^2 + b^2)/3).
Mat3 boxInertia(const Vec3& h) {
  return Vec3((h.y() * h.y() + h.z() * h.z()) / 3.0, (h.x() * h.x() + h.z() * h.z()) / 3.0,
              (h.x() * h.x() + h.y() * h.y()) / 3.0)
      .asDiagonal();
}

TriangleMesh withReversedWinding(const TriangleMesh& mesh) {
  std::vector<Triangle> triangles = mesh.triangles();
  for (Triangle& t : triangles) std::swap(t[1], t[2]);
  return TriangleMesh(mesh.vertices(), triangles, mesh.name());
}

// Every triangle gets its own three vertex copies (an STL-style soup).
TriangleMesh unwelded(const TriangleMesh& mesh) {
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;
  for (const Triangle& t : mesh.triangles()) {
    const auto base = static_cast<std::uint32_t>(vertices.size());
    for (int k = 0; k < 3; ++k) vertices.push_back(mesh.vertices()[t[k]]);
    triangles.push_back({base, base + 1, base + 2});
  }
  return TriangleMesh(vertices, triangles, mesh.name());
}

const Mat3& someRotation() {
  static const Mat3 r =
      Eigen::AngleAxisd(0.7, Vec3(1.0, -2.0, 0.5).normalized()).toRotationMatrix();
  return r;
}

// ---------------------------------------------------------------------------------------------
// Box

TEST(MassProperties, BoxMatchesAnalytic) {
  const Vec3 h(1, 2, 3);
  const MassProperties p = computeMassProperties(gen::makeBox(h));
  EXPECT_EQ(p.model, MassModel::SolidVolume);
  EXPECT_TRUE(p.closed);
  EXPECT_TRUE(relNear(p.volume, 48.0, 1e-12));
  EXPECT_TRUE(relNear(p.area, 8.0 * (2 + 6 + 3), 1e-12));
  EXPECT_TRUE(vecNear(p.centerOfMass, Vec3::Zero(), 1e-12));
  EXPECT_TRUE(matNear(p.inertia, boxInertia(h), 1e-12));
  EXPECT_TRUE(relNear(p.inertia(0, 0), 13.0 / 3.0, 1e-12));
  EXPECT_TRUE(relNear(p.inertia(1, 1), 10.0 / 3.0, 1e-12));
  EXPECT_TRUE(relNear(p.inertia(2, 2), 5.0 / 3.0, 1e-12));
  EXPECT_TRUE(relNear(p.principalMoments[0], 5.0 / 3.0, 1e-12));
  EXPECT_TRUE(relNear(p.principalMoments[2], 13.0 / 3.0, 1e-12));
  expectValidFrame(p);
}

TEST(MassProperties, BoxSubdividedMatchesBox) {
  const Vec3 h(1, 2, 3);
  const MassProperties coarse = computeMassProperties(gen::makeBox(h, 1));
  for (int subdivisions : {2, 4, 7}) {
    const MassProperties fine = computeMassProperties(gen::makeBox(h, subdivisions));
    EXPECT_EQ(fine.model, MassModel::SolidVolume);
    EXPECT_TRUE(relNear(fine.volume, coarse.volume, 1e-12));
    EXPECT_TRUE(relNear(fine.area, coarse.area, 1e-12));
    EXPECT_TRUE(vecNear(fine.centerOfMass, coarse.centerOfMass, 1e-12));
    EXPECT_TRUE(matNear(fine.inertia, boxInertia(h), 1e-12));
  }
}

TEST(MassProperties, BoxTranslatedRotatedGivesRotatedTensor) {
  const Vec3 h(1, 2, 3), t(0.5, -3.25, 7.0);
  const Mat3& r = someRotation();
  const MassProperties p = computeMassProperties(gen::transformed(gen::makeBox(h), Pose{r, t}));
  EXPECT_EQ(p.model, MassModel::SolidVolume);
  EXPECT_TRUE(relNear(p.volume, 48.0, 1e-12));
  EXPECT_TRUE(vecNear(p.centerOfMass, t, 1e-12 * t.norm()));
  EXPECT_TRUE(matNear(p.inertia, r * boxInertia(h) * r.transpose(), 1e-12));
  expectValidFrame(p);
  // Distinct moments: the axes are the box axes up to sign, ascending moment = longest half
  // extent's axis (z) first.
  EXPECT_NEAR(std::abs(p.principalAxes.col(0).dot(r.col(2))), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(p.principalAxes.col(1).dot(r.col(1))), 1.0, 1e-12);
  EXPECT_NEAR(std::abs(p.principalAxes.col(2).dot(r.col(0))), 1.0, 1e-12);
}

TEST(MassProperties, BoxTouchingBoxesStaySolidByIndex) {
  // Two unit boxes sharing the face x = 0 by position (not by index): closed per part by index,
  // while welding the shared positions would make that face's edges non-manifold.
  const TriangleMesh left = gen::transformed(gen::makeBox(Vec3(1, 1, 1)),
                                             Pose{Mat3::Identity(), Vec3(-1, 0, 0)});
  const TriangleMesh right = gen::transformed(gen::makeBox(Vec3(1, 1, 1)),
                                              Pose{Mat3::Identity(), Vec3(1, 0, 0)});
  const MassProperties p = computeMassProperties(gen::merge({left, right}));
  EXPECT_EQ(p.model, MassModel::SolidVolume);
  EXPECT_TRUE(p.closed);
  EXPECT_TRUE(relNear(p.volume, 16.0, 1e-12));
  EXPECT_TRUE(matNear(p.inertia, boxInertia(Vec3(2, 1, 1)), 1e-12));
}

TEST(MassProperties, BoxUnweldedSoupIsClosedByPosition) {
  const Vec3 h(1, 2, 3);
  const MassProperties p = computeMassProperties(unwelded(gen::makeBox(h, 3)));
  EXPECT_EQ(p.model, MassModel::SolidVolume);
  EXPECT_TRUE(p.closed);
  EXPECT_TRUE(relNear(p.volume, 48.0, 1e-12));
  EXPECT_TRUE(matNear(p.inertia, boxInertia(h), 1e-12));
}

// ---------------------------------------------------------------------------------------------
// Curved solids

TEST(MassProperties, SphereWithinOnePercentOfAnalytic) {
  const double r = 1.5;
  const MassProperties p = computeMassProperties(gen::makeSphere(r, 32));
  EXPECT_EQ(p.model, MassModel::SolidVolume);
  EXPECT_TRUE(p.closed);
  EXPECT_TRUE(relNear(p.volume, 4.0 / 3.0 * kPi * r * r * r, 0.01));
  EXPECT_TRUE(relNear(p.area, 4.0 * kPi * r * r, 0.01));
  EXPECT_TRUE(vecNear(p.centerOfMass, Vec3::Zero(), 1e-12));
  const double expected = 0.4 * r * r;
  for (int a = 0; a < 3; ++a) {
    EXPECT_TRUE(relNear(p.inertia(a, a), expected, 0.01));
    EXPECT_TRUE(relNear(p.principalMoments[a], expected, 0.01));
  }
  expectValidFrame(p);
}

TEST(MassProperties, TorusWithinTwoPercentOfAnalytic) {
  const double bigR = 1.0, r = 0.3;
  const MassProperties p = computeMassProperties(gen::makeTorus(bigR, r, 128, 64));
  EXPECT_EQ(p.model, MassModel::SolidVolume);
  EXPECT_TRUE(p.closed);
  EXPECT_TRUE(relNear(p.volume, 2.0 * kPi * kPi * bigR * r * r, 0.02));
  EXPECT_TRUE(vecNear(p.centerOfMass, Vec3::Zero(), 1e-12));
  const double izz = bigR * bigR + 0.75 * r * r;
  const double ixx = 0.5 * bigR * bigR + 0.625 * r * r;
  EXPECT_TRUE(relNear(p.inertia(0, 0), ixx, 0.02));
  EXPECT_TRUE(relNear(p.inertia(1, 1), ixx, 0.02));
  EXPECT_TRUE(relNear(p.inertia(2, 2), izz, 0.02));
  EXPECT_TRUE(relNear(p.principalMoments[2], izz, 0.02));
  expectValidFrame(p);
}

TEST(MassProperties, CylinderVolumeIsExactPrismVolume) {
  const double r = 0.5, height = 2.0;
  const int segments = 24;
  const MassProperties p = computeMassProperties(gen::makeCylinder(r, height, segments, 3, 2));
  EXPECT_EQ(p.model, MassModel::SolidVolume);
  EXPECT_TRUE(relNear(p.volume, 0.5 * segments * r * r * std::sin(2 * kPi / segments) * height,
                      1e-12));
  EXPECT_TRUE(vecNear(p.centerOfMass, Vec3::Zero(), 1e-12));
  // The prism's Izz tends to r^2 / 2 (within about 1 % at 24 segments).
  EXPECT_TRUE(relNear(p.inertia(2, 2), 0.5 * r * r, 0.02));
}

TEST(MassProperties, NamedModelsAreClosedSolids) {
  for (const std::string& name : gen::modelNames()) {
    SCOPED_TRACE(name);
    const MassProperties p = computeMassProperties(gen::makeModel(name, 2000));
    EXPECT_EQ(p.model, MassModel::SolidVolume);
    EXPECT_TRUE(p.closed);
    EXPECT_GT(p.volume, 0.0);
    expectValidFrame(p);
  }
}

// ---------------------------------------------------------------------------------------------
// Winding

TEST(MassProperties, InvertedWindingGivesSameResultAndClosed) {
  for (const TriangleMesh& mesh :
       {gen::transformed(gen::makeBox(Vec3(1, 2, 3), 2), Pose{someRotation(), Vec3(3, 2, 1)}),
        gen::makeTorus(1.0, 0.3, 24, 12), gen::makeTorusKnot(2, 3, 1.0, 0.12, 96, 12)}) {
    const MassProperties out = computeMassProperties(mesh);
    const MassProperties in = computeMassProperties(withReversedWinding(mesh));
    EXPECT_EQ(in.model, MassModel::SolidVolume);
    EXPECT_TRUE(in.closed);
    EXPECT_TRUE(relNear(in.volume, out.volume, 1e-12));
    EXPECT_TRUE(relNear(in.area, out.area, 1e-12));
    EXPECT_TRUE(vecNear(in.centerOfMass, out.centerOfMass, 1e-12));
    EXPECT_TRUE(matNear(in.inertia, out.inertia, 1e-12));
    expectValidFrame(in);
  }
}

TEST(MassProperties, InconsistentWindingFallsBackToShell) {
  const TriangleMesh box = gen::makeBox(Vec3(1, 2, 3));
  std::vector<Triangle> triangles = box.triangles();
  std::swap(triangles[5][1], triangles[5][2]);
  const MassProperties p = computeMassProperties(TriangleMesh(box.vertices(), triangles));
  EXPECT_FALSE(p.closed);
  EXPECT_EQ(p.model, MassModel::ThinShell);
  EXPECT_EQ(p.volume, 0.0);
  // The shell ignores winding, so it equals the box's surface shell (checked in the next test
  // family); here: same area as the intact box.
  EXPECT_TRUE(relNear(p.area, 88.0, 1e-12));
  expectValidFrame(p);
}

// ---------------------------------------------------------------------------------------------
// Thin-shell fallback

TEST(MassProperties, OpenMeshFallbackFlatSquareGrid) {
  // Flat square shell of side a: Izz = a^2 / 6, Ixx = Iyy = a^2 / 12 (unit mass), exact.
  const double a = 2.5;
  const MassProperties p = computeMassProperties(gen::makeFlatGrid(a, a, 8, 8));
  EXPECT_EQ(p.model, MassModel::ThinShell);
  EXPECT_FALSE(p.closed);
  EXPECT_EQ(p.volume, 0.0);
  EXPECT_TRUE(relNear(p.area, a * a, 1e-12));
  EXPECT_TRUE(vecNear(p.centerOfMass, Vec3::Zero(), 1e-12));
  const Mat3 expected = Vec3(a * a / 12, a * a / 12, a * a / 6).asDiagonal();
  EXPECT_TRUE(matNear(p.inertia, expected, 1e-12));
  expectValidFrame(p);
}

TEST(MassProperties, OpenMeshFallbackFlatRectangleGrid) {
  const double sx = 2.0, sy = 3.0;
  const MassProperties p = computeMassProperties(gen::makeFlatGrid(sx, sy, 3, 5));
  EXPECT_EQ(p.model, MassModel::ThinShell);
  const Mat3 expected = Vec3(sy * sy / 12, sx * sx / 12, (sx * sx + sy * sy) / 12).asDiagonal();
  EXPECT_TRUE(matNear(p.inertia, expected, 1e-12));
  EXPECT_TRUE(relNear(p.principalMoments[2], p.principalMoments[0] + p.principalMoments[1],
                      1e-12));  // perpendicular-axis theorem
  expectValidFrame(p);
}

TEST(MassProperties, OpenMeshFallbackBoxWithoutTopFace) {
  // Box [-h, h] without its z = +c face, as a uniform shell. Each full face is a rectangle with
  // zero products of inertia about the origin, so the expected numbers sum face by face.
  const Vec3 h(1, 2, 3);
  const TriangleMesh box = gen::makeBox(h, 2);
  std::vector<Triangle> kept;
  for (const Triangle& t : box.triangles()) {
    bool top = true;
    for (int k = 0; k < 3; ++k) top = top && box.vertices()[t[k]].z() == h.z();
    if (!top) kept.push_back(t);
  }
  ASSERT_EQ(kept.size(), box.triangleCount() - 8);
  const MassProperties p = computeMassProperties(TriangleMesh(box.vertices(), kept));
  EXPECT_EQ(p.model, MassModel::ThinShell);
  EXPECT_FALSE(p.closed);

  double area = 0.0, firstZ = 0.0;
  Vec3 second = Vec3::Zero();  // integral of x^2, y^2, z^2 about the origin
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    for (int side : {-1, 1}) {
      if (axis == 2 && side == 1) continue;  // the removed face
      const double faceArea = 4.0 * h[u] * h[v];
      area += faceArea;
      if (axis == 2) firstZ += faceArea * side * h.z();
      second[axis] += faceArea * h[axis] * h[axis];
      second[u] += faceArea * h[u] * h[u] / 3.0;
      second[v] += faceArea * h[v] * h[v] / 3.0;
    }
  }
  const Vec3 com(0, 0, firstZ / area);
  Vec3 cov = second / area;
  cov.z() -= com.z() * com.z();
  const Mat3 expected = Vec3(cov.y() + cov.z(), cov.x() + cov.z(), cov.x() + cov.y()).asDiagonal();
  EXPECT_TRUE(relNear(p.area, area, 1e-12));
  EXPECT_TRUE(vecNear(p.centerOfMass, com, 1e-12));
  EXPECT_TRUE(matNear(p.inertia, expected, 1e-12));
  expectValidFrame(p);
}

TEST(MassProperties, OpenMeshFallbackTwoSidedTriangleIsClosedButFlat) {
  // (0,1,2) and (0,2,1): every directed edge once with its reverse, so closed, but the enclosed
  // volume is zero: the shell model, with both sides counted in the area.
  const std::vector<Vec3> v = {{0, 0, 0}, {2, 0, 0}, {0, 1, 0}};
  const MassProperties p = computeMassProperties(TriangleMesh(v, {{0, 1, 2}, {0, 2, 1}}));
  EXPECT_TRUE(p.closed);
  EXPECT_EQ(p.model, MassModel::ThinShell);
  EXPECT_TRUE(relNear(p.area, 2.0, 1e-12));
  const MassProperties one = computeMassProperties(TriangleMesh(v, {{0, 1, 2}}));
  EXPECT_TRUE(matNear(p.inertia, one.inertia, 1e-12));
}

// ---------------------------------------------------------------------------------------------
// Degenerate input

TEST(MassProperties, AllDegenerateGivesPointMassAtBoundsCentre) {
  // A collinear triangle and a repeated-vertex one: zero area.
  const std::vector<Vec3> v = {{0, 0, 0}, {1, 1, 0}, {2, 2, 0}, {4, 0, 2}};
  const TriangleMesh mesh(v, {{0, 1, 2}, {3, 3, 0}});
  ASSERT_EQ(mesh.report().degenerateTriangles, 2u);
  const MassProperties p = computeMassProperties(mesh);
  EXPECT_EQ(p.model, MassModel::ThinShell);
  EXPECT_FALSE(p.closed);
  EXPECT_EQ(p.volume, 0.0);
  EXPECT_EQ(p.area, 0.0);
  EXPECT_TRUE(vecNear(p.centerOfMass, Vec3(2, 1, 1), 0.0));
  EXPECT_EQ(p.inertia, Mat3::Zero());
  EXPECT_EQ(p.principalMoments, Vec3::Zero());
  EXPECT_EQ(p.principalAxes, Mat3::Identity());
}

TEST(MassProperties, SingleTriangleHasNoNaN) {
  const std::vector<Vec3> v = {{0.3, -1.0, 2.0}, {1.7, 0.2, 2.5}, {-0.4, 0.9, 1.1}};
  const TriangleMesh mesh(v, {{0, 1, 2}});
  const MassProperties p = computeMassProperties(mesh);
  EXPECT_EQ(p.model, MassModel::ThinShell);
  EXPECT_FALSE(p.closed);
  EXPECT_EQ(p.volume, 0.0);
  EXPECT_TRUE(relNear(p.area, mesh.triangleArea(0), 1e-12));
  EXPECT_TRUE(vecNear(p.centerOfMass, (v[0] + v[1] + v[2]) / 3.0, 1e-12));
  expectValidFrame(p);
  // A lamina: the normal is the largest principal axis and its moment is the sum of the others.
  const Vec3 normal = (v[1] - v[0]).cross(v[2] - v[0]).normalized();
  EXPECT_NEAR(std::abs(p.principalAxes.col(2).dot(normal)), 1.0, 1e-12);
  EXPECT_TRUE(relNear(p.principalMoments[2], p.principalMoments[0] + p.principalMoments[1],
                      1e-12));
  EXPECT_GT(p.principalMoments[0], 0.0);
}

TEST(MassProperties, SliverTriangleAmongGoodOnesKeepsBoxNumbers) {
  // A box plus one collinear sliver on an existing edge (its own vertex in the middle): the
  // sliver adds no area or volume; its directed edges have no reverse, so the mesh is open.
  const TriangleMesh box = gen::makeBox(Vec3(1, 2, 3));
  std::vector<Vec3> v = box.vertices();
  std::vector<Triangle> t = box.triangles();
  const Triangle& first = t[0];
  v.push_back(0.5 * (v[first[0]] + v[first[1]]));
  t.push_back({first[0], static_cast<std::uint32_t>(v.size() - 1), first[1]});
  const MassProperties p = computeMassProperties(TriangleMesh(v, t));
  EXPECT_FALSE(p.closed);
  EXPECT_EQ(p.model, MassModel::ThinShell);
  EXPECT_TRUE(relNear(p.area, 88.0, 1e-12));
  expectValidFrame(p);
}

// ---------------------------------------------------------------------------------------------
// Precision and range

TEST(MassProperties, FarFromOriginMatchesOriginResult) {
  const Vec3 offset(1e5 + 0.3, -1e5 + 0.7, 0.5e5 + 0.1);
  const Mat3& r = someRotation();
  for (const TriangleMesh& mesh :
       {gen::makeBox(Vec3(1, 2, 3), 3), gen::makeTorus(1.0, 0.3, 48, 24),
        gen::makeFlatGrid(2.0, 3.0, 4, 6), gen::makeTorusKnot(2, 3, 1.0, 0.12, 96, 12)}) {
    SCOPED_TRACE(mesh.name());
    const MassProperties near =
        computeMassProperties(gen::transformed(mesh, Pose{r, Vec3::Zero()}));
    const MassProperties far = computeMassProperties(gen::transformed(mesh, Pose{r, offset}));
    EXPECT_EQ(far.model, near.model);
    EXPECT_EQ(far.closed, near.closed);
    const double size = mesh.bounds().extent().norm();
    EXPECT_TRUE(relNear(far.volume, near.volume, 1e-9));
    EXPECT_TRUE(relNear(far.area, near.area, 1e-9));
    EXPECT_TRUE(vecNear(far.centerOfMass - offset, near.centerOfMass, 1e-9 * size));
    EXPECT_TRUE(matNear(far.inertia, near.inertia, 1e-9));
    EXPECT_TRUE(((far.principalMoments - near.principalMoments).array().abs() <=
                 1e-9 * near.principalMoments.maxCoeff())
                    .all());
  }
}

TEST(MassProperties, FarFromOriginExtremeScalesStayExact) {
  // Power-of-two scaling inside: tiny and huge boxes give the scaled unit-box numbers. (Below
  // about 1e-75 TriangleMesh itself calls every triangle degenerate: its cross-product norm
  // underflows. That gives the point mass, tested elsewhere.)
  const Vec3 h(1, 2, 3);
  for (double s : {1e-60, 1e-30, 1e30, 1e100}) {
    SCOPED_TRACE(s);
    const MassProperties p = computeMassProperties(gen::makeBox(h * s));
    EXPECT_EQ(p.model, MassModel::SolidVolume);
    EXPECT_TRUE(relNear(p.volume, 48.0 * s * s * s, 1e-12));
    EXPECT_TRUE(relNear(p.area, 88.0 * s * s, 1e-12));
    EXPECT_TRUE(matNear(p.inertia, boxInertia(h) * (s * s), 1e-12));
    expectValidFrame(p);
  }
}

TEST(MassProperties, FarFromOriginOverflowNeverNaN) {
  // At 1e120 the volume (~1e361) overflows: the shell model (area ~1e241) is used instead. At
  // 1e200 TriangleMesh's degeneracy test overflows (inf <= 1e-12 * inf): a point mass.
  const MassProperties shell = computeMassProperties(gen::makeBox(Vec3(1, 2, 3) * 1e120));
  EXPECT_EQ(shell.model, MassModel::ThinShell);
  EXPECT_TRUE(shell.closed);
  EXPECT_GT(shell.area, 0.0);
  expectValidFrame(shell);
  const MassProperties point = computeMassProperties(gen::makeBox(Vec3(1, 2, 3) * 1e200));
  EXPECT_TRUE(allFinite(point));
  EXPECT_EQ(point.inertia, Mat3::Zero());
}

// ---------------------------------------------------------------------------------------------
// Principal frame

TEST(MassProperties, PrincipalAxesOrthonormalRightHandedAscending) {
  const std::vector<TriangleMesh> meshes = {
      gen::transformed(gen::makeBox(Vec3(3, 1, 2), 2), Pose{someRotation(), Vec3(1, 2, 3)}),
      gen::makeTorusKnot(3, 2, 1.0, 0.12, 96, 12),
      gen::makeGear(9, 1.0, 0.8, 0.3, 0.25, 6),
      gen::makeSphere(1.0, 6),  // nearly equal moments: any orthonormal frame, still det +1
      gen::makeFlatGrid(1.0, 4.0, 2, 3),
  };
  for (const TriangleMesh& mesh : meshes) {
    SCOPED_TRACE(mesh.name());
    expectValidFrame(computeMassProperties(mesh));
  }
}

}  // namespace
}  // namespace adb
