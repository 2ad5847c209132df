// Assemblies: a bundle of bent pipes, and the lock (plates, pins and a plug).
#include "adb/support/mesh_generators.h"

#include <array>
#include <cmath>

#include "generator_kit.h"

namespace adb::gen {
using namespace kit;  // the generators' shared parts
namespace {

// Pipe bundle

constexpr double kPipeBend = 0.5 * kPi;  // each pipe bends by 90 degrees

// One pipe along a horizontal 90-degree arc, its bend centred on x = 0. Lattice rows go around
// the pipe, columns along a closed annulus profile: outer wall from the far end back to the
// start, start cap inwards, inner wall forwards, far-end cap outwards. Rows and columns are
// swapped relative to the knot tube, which flips the winding; running the outer wall backwards
// flips it back, so the lattice winds outward (and the inner wall faces the pipe's axis).
Builder pipePart(double length, double radius, double wall, int segments, int lengthSegments) {
  const double bend = length / kPipeBend;
  const double centreX = -0.5 * bend * (1.0 + std::cos(0.5 * kPipeBend));
  const int ring = lengthSegments + 1;
  const auto frameAt = [&](int k) {
    const double phi = -0.5 * kPipeBend + kPipeBend * fraction(k, lengthSegments);
    const Vec3 n(std::cos(phi), std::sin(phi), 0.0), tangent(-std::sin(phi), std::cos(phi), 0.0);
    return Frame{Vec3(centreX, 0, 0) + bend * n, n, n.cross(tangent)};
  };
  Builder b;
  addGrid(b, segments, 2 * ring, true, true, [&](int i, int j) {
    const bool outer = j < ring;
    const int k = outer ? lengthSegments - j : j - ring;
    return frameAt(k).ring(outer ? radius : radius - wall, angle(i, segments));
  });
  return b;
}


// Lock assembly

struct LockBox {
  Vec3 centre, half;
};
struct LockCylinder {
  Vec3 centre, axis;
  double radius, height;
};

// Housing plate and bolt; the bolt runs through the plate's right edge.
const std::array<LockBox, 2> kLockBoxes = {{
    {Vec3(0.0, 0.0, 0.0), Vec3(0.75, 0.5, 0.1)},
    {Vec3(0.6, -0.05, 0.0), Vec3(0.4, 0.1, 0.06)},
}};

// Plug through the plate, three pins above it, two screws (one along y, so that a rotated
// part is part of the model).
const std::array<LockCylinder, 6> kLockCylinders = {{
    {Vec3(-0.3, 0.0, 0.0), Vec3::UnitZ(), 0.22, 0.36},
    {Vec3(-0.42, 0.32, 0.0), Vec3::UnitZ(), 0.04, 0.3},
    {Vec3(-0.30, 0.32, 0.0), Vec3::UnitZ(), 0.04, 0.3},
    {Vec3(-0.18, 0.32, 0.0), Vec3::UnitZ(), 0.04, 0.3},
    {Vec3(0.6, 0.38, 0.0), Vec3::UnitZ(), 0.05, 0.26},
    {Vec3(0.6, -0.38, 0.0), Vec3::UnitY(), 0.05, 0.26},
}};

int cellsFor(double length, double edge, int minimum) {
  return std::max(minimum, static_cast<int>(std::lround(length / edge)));
}

std::array<int, 3> lockBoxCells(const LockBox& box, double edge) {
  return {cellsFor(2 * box.half.x(), edge, 1), cellsFor(2 * box.half.y(), edge, 1),
          cellsFor(2 * box.half.z(), edge, 1)};
}

// (segments, heightSegments, capRings) for a lock cylinder.
std::array<int, 3> lockCylinderCells(const LockCylinder& c, double edge) {
  return {cellsFor(2 * kPi * c.radius, edge, 8), cellsFor(c.height, edge, 1),
          cellsFor(c.radius, edge, 1)};
}

}  // namespace

TriangleMesh makePipeBundle(int pipes, double length, double radius, double wallThickness,
                            int segments, int lengthSegments) {
  const char* fn = "makePipeBundle";
  requireAtLeast(fn, "pipes", pipes, 1);
  requirePositive(fn, "radius", radius);
  requirePositive(fn, "wallThickness", wallThickness);
  require(wallThickness < radius, fn, "wallThickness must be below radius" + got(wallThickness));
  // The bend radius (length / (pi/2)) must exceed the pipe radius or the wall folds over.
  require(length > kPipeBend * radius, fn, "length must exceed pi/2 * radius" + got(length));
  requireAtLeast(fn, "segments", segments, 3);
  requireAtLeast(fn, "lengthSegments", lengthSegments, 1);
  requireCount(fn, 4.0 * pipes * static_cast<double>(segments) * (lengthSegments + 1.0));
  const Builder pipe = pipePart(length, radius, wallThickness, segments, lengthSegments);
  const double layer = 2.5 * radius;  // pipe diameter plus a gap of half a radius
  Builder b;
  for (int k = 0; k < pipes; ++k) {
    const double z = (k - 0.5 * (pipes - 1)) * layer;
    b.append(pipe, Pose{rotationZ(kPi * k / pipes), Vec3(0, 0, z)});
  }
  return b.finish("pipe_bundle");
}

TriangleMesh makeLockAssembly(int resolution) {
  const char* fn = "makeLockAssembly";
  requireAtLeast(fn, "resolution", resolution, 1);
  requireCount(fn, lockTriangleCount(resolution));
  const double edge = 1.0 / resolution;
  Builder b;
  for (const LockBox& box : kLockBoxes) {
    b.append(boxPart(box.half, lockBoxCells(box, edge)), Pose{Mat3::Identity(), box.centre});
  }
  for (const LockCylinder& c : kLockCylinders) {
    const auto n = lockCylinderCells(c, edge);
    const Eigen::Quaterniond toAxis = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), c.axis);
    b.append(cylinderPart(c.radius, c.height, n[0], n[1], n[2]),
             Pose::fromQuaternion(toAxis, c.centre));
  }
  return b.finish("lock_assembly");
}

}  // namespace adb::gen

namespace adb::gen::kit {

// The same count makeLockAssembly(resolution) produces, without building it.
double lockTriangleCount(int resolution) {
  const double edge = 1.0 / resolution;
  double count = 0.0;
  for (const LockBox& box : kLockBoxes) {
    const auto n = lockBoxCells(box, edge);
    count += 4.0 * (n[0] * n[1] + n[1] * n[2] + n[2] * n[0]);
  }
  for (const LockCylinder& c : kLockCylinders) {
    const auto n = lockCylinderCells(c, edge);
    count += 2.0 * n[0] * (n[1] + 2 * n[2] - 1);
  }
  return count;
}

}  // namespace adb::gen::kit
