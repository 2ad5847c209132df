// Meshes shaped like the ones real scenes bring, not like the benchmark's well-shaped models:
// the sliver cylinder (a CAD exporter's cylinder), a furnished room and a low-poly robot arm
// (the scene of FCL's test suite: a robot at random poses in an environment). What makes
// them hard for a bounding-volume tree is their triangles: long slivers whose boxes are
// mostly empty, and large flat walls whose boxes span the scene.
#include "adb/support/mesh_generators.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "generator_kit.h"

namespace adb::gen {
using namespace kit;  // the generators' shared parts
namespace {

// Solid cylinder along z, centred: side rows of quads (lattice rows around, columns up, so it
// winds outward: d/d(angle) x d/dz is the outward radial), each cap a fan from rim vertex 0.
// Each cap's fan uses the reverse of every rim edge the side uses, so the part is closed by
// index.
Builder sliverCylinderPart(double radius, double height, int segments, int heightSegments) {
  Builder b;
  const int levels = heightSegments + 1;
  addGrid(b, segments, levels, true, false, [&](int i, int j) {
    const double t = angle(i, segments);
    return Vec3(radius * std::cos(t), radius * std::sin(t),
                -0.5 * height + height * fraction(j, heightSegments));
  });
  const auto rim = [&](int i, int level) {
    return static_cast<std::uint32_t>(i * levels + level);
  };
  for (int i = 1; i + 1 < segments; ++i) {
    b.triangle(rim(0, 0), rim(i + 1, 0), rim(i, 0));  // bottom: counter-clockwise from below
    b.triangle(rim(0, levels - 1), rim(i, levels - 1), rim(i + 1, levels - 1));
  }
  return b;
}

// ---------------------------------------------------------------------------------------------
// The room: 6 x 6 x 3, centred at the origin, the floor at z = -1.5. Every piece keeps at
// least 1 cm from the shell (the floor included): a piece standing on the floor would lie in
// its plane, a contact no query of the room is about.

constexpr double kFloor = -1.5;
const Vec3 kRoomHalf(3.0, 3.0, 1.5);

// A part placed in the room: a box (half extents) or a sliver cylinder along `axis`.
struct RoomBox {
  Vec3 centre, half;
  double turn = 0.0;  ///< radians about z
};
struct RoomCylinder {
  Vec3 centre, axis;
  double radius, length;
  int segments;
};

Pose poseAlong(const Vec3& centre, const Vec3& axis) {
  return Pose::fromQuaternion(Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), axis), centre);
}

void addBox(Builder& b, const RoomBox& box) {
  b.append(boxPart(box.half, {1, 1, 1}), Pose{rotationZ(box.turn), box.centre});
}

void addCylinder(Builder& b, const RoomCylinder& c) {
  b.append(sliverCylinderPart(c.radius, c.length, c.segments, 1), poseAlong(c.centre, c.axis));
}

// The shell: eight corners and the six faces, two triangles each, wound to face the inside
// (each quad is listed counter-clockwise seen from inside the room).
void addShell(Builder& b) {
  std::array<std::uint32_t, 8> corner{};  // corner k: bit 0 says +x, bit 1 +y, bit 2 +z
  for (int k = 0; k < 8; ++k) {
    const Vec3 sign(k & 1 ? 1.0 : -1.0, k & 2 ? 1.0 : -1.0, k & 4 ? 1.0 : -1.0);
    corner[static_cast<std::size_t>(k)] = b.vertex(sign.cwiseProduct(kRoomHalf));
  }
  const auto quad = [&](int p, int q, int r, int s) {
    b.quad(corner[static_cast<std::size_t>(p)], corner[static_cast<std::size_t>(q)],
           corner[static_cast<std::size_t>(r)], corner[static_cast<std::size_t>(s)]);
  };
  quad(0, 1, 3, 2);  // floor (z-), normal +z
  quad(4, 6, 7, 5);  // ceiling (z+), normal -z
  quad(0, 4, 5, 1);  // wall y-, normal +y
  quad(2, 3, 7, 6);  // wall y+, normal -y
  quad(0, 2, 6, 4);  // wall x-, normal +x
  quad(1, 5, 7, 3);  // wall x+, normal -x
}

// A table at (x, y): a thin top on four sliver-cylinder legs.
void addTable(Builder& b, double x, double y) {
  addBox(b, {Vec3(x, y, kFloor + 0.73), Vec3(0.8, 0.45, 0.02)});
  for (const double sx : {-0.72, 0.72}) {
    for (const double sy : {-0.38, 0.38}) {
      addCylinder(b, {Vec3(x + sx, y + sy, kFloor + 0.36), Vec3::UnitZ(), 0.025, 0.7, 12});
    }
  }
}

// A chair at (x, y) turned by `turn` about z: seat, four legs and a back, all boxes.
void addChair(Builder& b, double x, double y, double turn) {
  const Mat3 r = rotationZ(turn);
  const Vec3 at(x, y, 0.0);
  const auto place = [&](const Vec3& local, const Vec3& half) {
    addBox(b, {at + r * local, half, turn});
  };
  place(Vec3(0, 0, kFloor + 0.45), Vec3(0.22, 0.22, 0.01));
  for (const double sx : {-0.2, 0.2}) {
    for (const double sy : {-0.2, 0.2}) {
      place(Vec3(sx, sy, kFloor + 0.225), Vec3(0.008, 0.008, 0.215));
    }
  }
  place(Vec3(0, 0.21, kFloor + 0.71), Vec3(0.22, 0.01, 0.25));
}

// A bookshelf against the wall x = -3: two sides, five shelves, a back panel (boards 12 mm
// thick).
void addBookshelf(Builder& b) {
  const double x = -kRoomHalf.x() + 0.2;
  for (const double y : {-0.5, 0.5}) {
    addBox(b, {Vec3(x, y, kFloor + 0.91), Vec3(0.15, 0.006, 0.9)});
  }
  for (int k = 0; k < 5; ++k) {
    addBox(b, {Vec3(x, 0, kFloor + 0.03 + 0.44 * k), Vec3(0.15, 0.494, 0.006)});
  }
  addBox(b, {Vec3(x - 0.14, 0, kFloor + 0.91), Vec3(0.004, 0.5, 0.9)});
}

// A sofa against the wall y = +3: seat, back, two arms.
void addSofa(Builder& b) {
  const double y = kRoomHalf.y() - 0.5;
  addBox(b, {Vec3(0.5, y, kFloor + 0.22), Vec3(1.0, 0.45, 0.2)});
  addBox(b, {Vec3(0.5, y + 0.35, kFloor + 0.6), Vec3(1.0, 0.1, 0.35)});
  for (const double x : {-0.6, 1.6}) addBox(b, {Vec3(x, y, kFloor + 0.32), Vec3(0.1, 0.45, 0.3)});
}

// On the wall y = -3: a radiator of thin fins on two pipes, and above it a window: its frame
// (two rails, two stiles and a mullion) and a blind of twenty slats.
void addWindowWall(Builder& b) {
  const double y = -kRoomHalf.y() + 0.1;
  for (int k = 0; k < 16; ++k) {
    addBox(b, {Vec3(-0.45 + 0.06 * k, y, kFloor + 0.5), Vec3(0.002, 0.04, 0.3)});
  }
  for (const double z : {kFloor + 0.3, kFloor + 0.7}) {
    addCylinder(b, {Vec3(0, y, z), Vec3::UnitX(), 0.015, 1.1, 12});
  }
  const double wy = -kRoomHalf.y() + 0.035, wz = 0.3;
  for (const double dz : {-0.6, 0.6}) addBox(b, {Vec3(0, wy, wz + dz), Vec3(0.8, 0.025, 0.025)});
  for (const double dx : {-0.775, 0.0, 0.775}) {
    addBox(b, {Vec3(dx, wy, wz), Vec3(0.025, 0.025, 0.575)});
  }
  for (int k = 0; k < 20; ++k) {
    addBox(b, {Vec3(0, wy + 0.08, wz - 0.55 + 0.057 * k), Vec3(0.75, 0.02, 0.001)});
  }
}

// A door frame on the wall x = +3: two jambs and a head.
void addDoorFrame(Builder& b) {
  const double x = kRoomHalf.x() - 0.06;
  for (const double y : {-1.5, -0.5}) {
    addBox(b, {Vec3(x, y, kFloor + 1.02), Vec3(0.05, 0.025, 1.0)});
  }
  addBox(b, {Vec3(x, -1.0, kFloor + 2.045), Vec3(0.05, 0.525, 0.025)});
}

// Skirting boards along the four walls, 1 cm off each wall and the floor.
void addSkirting(Builder& b) {
  const double in = 0.02, h = 0.04, along = 2.9;
  addBox(b, {Vec3(0, kRoomHalf.y() - in, kFloor + 0.01 + h), Vec3(along, 0.008, h)});
  addBox(b, {Vec3(0, -kRoomHalf.y() + in, kFloor + 0.01 + h), Vec3(along, 0.008, h)});
  addBox(b, {Vec3(kRoomHalf.x() - in, 0, kFloor + 0.01 + h), Vec3(0.008, along, h)});
  addBox(b, {Vec3(-kRoomHalf.x() + in, 0, kFloor + 0.01 + h), Vec3(0.008, along, h)});
}

// Under the ceiling: two long pipes along y, and a strip light (a housing and its tube) hung
// from two cords.
void addCeiling(Builder& b) {
  for (const double x : {-1.0, 1.0}) {
    addCylinder(b, {Vec3(x, 0, kRoomHalf.z() - 0.1), Vec3::UnitY(), 0.04, 5.9, 16});
  }
  const Vec3 light(0.9, -0.6, kRoomHalf.z() - 0.5);
  addBox(b, {light, Vec3(0.6, 0.06, 0.02)});
  addCylinder(b, {light - Vec3(0, 0, 0.035), Vec3::UnitX(), 0.015, 1.1, 12});
  for (const double dx : {-0.5, 0.5}) {
    addCylinder(b, {light + Vec3(dx, 0, 0.22), Vec3::UnitZ(), 0.003, 0.4, 6});
  }
}

// ---------------------------------------------------------------------------------------------
// The robot arm: built standing on z = 0 reaching along +x, then centred.

// A link of half extents `half` whose long (z) axis points along `direction` from `from`.
void addLink(Builder& b, const Vec3& from, const Vec3& direction, const Vec3& half) {
  b.append(boxPart(half, {1, 1, 1}), poseAlong(from + half.z() * direction, direction));
}

void addJoint(Builder& b, const Vec3& centre, const Vec3& axis, double radius, double length,
              int segments) {
  b.append(sliverCylinderPart(radius, length, segments, 1), poseAlong(centre, axis));
}

}  // namespace

TriangleMesh makeSliverCylinder(double radius, double height, int segments, int heightSegments) {
  const char* fn = "makeSliverCylinder";
  requirePositive(fn, "radius", radius);
  requirePositive(fn, "height", height);
  requireAtLeast(fn, "segments", segments, 3);
  requireAtLeast(fn, "heightSegments", heightSegments, 1);
  requireCount(fn, 2.0 * segments * (static_cast<double>(heightSegments) + 1.0));
  return sliverCylinderPart(radius, height, segments, heightSegments).finish("sliver_cylinder");
}

TriangleMesh makeRoom() {
  Builder b;
  addShell(b);
  addTable(b, 1.0, -0.6);
  // Four chairs around the table, their backs (at a chair's local +y) away from it.
  addChair(b, 1.0, -1.35, kPi);
  addChair(b, 1.0, 0.15, 0.0);
  addChair(b, -0.1, -0.6, 0.5 * kPi);
  addChair(b, 2.1, -0.6, -0.5 * kPi);
  addBookshelf(b);
  addSofa(b);
  addWindowWall(b);
  addDoorFrame(b);
  addSkirting(b);
  addCeiling(b);
  return b.finish("room");
}

TriangleMesh makeRobotArm() {
  Builder b;
  // Base and turret on the floor, the shoulder's axis along y.
  addJoint(b, Vec3(0, 0, 0.025), Vec3::UnitZ(), 0.12, 0.05, 16);
  addJoint(b, Vec3(0, 0, 0.11), Vec3::UnitZ(), 0.07, 0.12, 12);
  const Vec3 shoulder(0, 0, 0.2);
  addJoint(b, shoulder, Vec3::UnitY(), 0.06, 0.12, 12);
  // Upper arm 0.4 long, 30 degrees from the vertical; forearm 0.34, 100 degrees (reaching
  // forward and a little down).
  const Vec3 up(std::sin(kPi / 6), 0, std::cos(kPi / 6));
  addLink(b, shoulder, up, Vec3(0.03, 0.035, 0.2));
  const Vec3 elbow = shoulder + 0.4 * up;
  addJoint(b, elbow, Vec3::UnitY(), 0.045, 0.1, 12);
  const Vec3 forward(std::sin(kPi * 100 / 180), 0, std::cos(kPi * 100 / 180));
  addLink(b, elbow, forward, Vec3(0.025, 0.03, 0.17));
  const Vec3 wrist = elbow + 0.34 * forward;
  addJoint(b, wrist, forward, 0.03, 0.06, 12);
  // The gripper: a palm across the forearm, two fingers along it.
  const Vec3 palm = wrist + 0.04 * forward;
  b.append(boxPart(Vec3(0.02, 0.06, 0.02), {1, 1, 1}),
           poseAlong(palm, forward));  // its y half extent spans the fingers
  for (const double side : {-0.045, 0.045}) {
    addLink(b, palm + Vec3(0, side, 0), forward, Vec3(0.008, 0.01, 0.05));
  }
  const TriangleMesh standing = b.finish("robot_arm");
  return transformed(standing, Pose{Mat3::Identity(), -standing.bounds().center()});
}

double triangleAspect(const TriangleMesh& mesh, std::size_t i) {
  const Triangle& t = mesh.triangles()[i];
  const Vec3 &a = mesh.vertices()[t[0]], &b = mesh.vertices()[t[1]], &c = mesh.vertices()[t[2]];
  const double longest2 =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  const double twiceArea = (b - a).cross(c - a).norm();
  return twiceArea > 0.0 ? longest2 / twiceArea : std::numeric_limits<double>::infinity();
}

double medianAspect(const TriangleMesh& mesh) {
  const std::size_t n = mesh.triangleCount();
  if (n == 0) return 0.0;
  std::vector<double> aspects(n);
  for (std::size_t i = 0; i < n; ++i) aspects[i] = triangleAspect(mesh, i);
  const auto middle = aspects.begin() + static_cast<std::ptrdiff_t>(n / 2);
  std::nth_element(aspects.begin(), middle, aspects.end());
  return *middle;
}

}  // namespace adb::gen
