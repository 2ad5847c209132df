#include "adb/scene/pile_scene.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>

#include "adb/support/benchmark_poses.h"
#include "adb/support/mesh_generators.h"

namespace adb::scene {
namespace {

constexpr double kBodySize = 0.8;  // across, the largest extent of a body from a file
constexpr double kFriction = 0.6;
// Far above anything the pile throws: a body is lost through the floor or a wall, not upwards.
constexpr double kBoundsTop = 1000.0;

// The three kinds of generated body, at about `triangles` triangles each, ~0.8 units across.
std::vector<TriangleMesh> generatedBodies(std::size_t triangles) {
  const double t = static_cast<double>(triangles);
  const int ring = std::max(6, static_cast<int>(std::sqrt(t / 4.0)));
  const int tooth = std::max(4, static_cast<int>(t / 80.0));
  const int along = std::max(24, static_cast<int>(t / 16.0));
  return {gen::makeTorus(0.35, 0.12, 2 * ring, ring),
          gen::makeGear(10, 0.4, 0.32, 0.15, 0.15, tooth),
          gen::makeTorusKnot(2, 3, 0.3, 0.045, along, 8)};
}

struct BinPart {
  const char* name;
  Vec3 half, centre;
};

// The floor (first: Floor::Plane replaces it), its top at y = 0, and four walls whose inner
// faces are 2.5 from the centre.
const BinPart kBin[] = {{"floor", Vec3(2.5, 0.25, 2.5), Vec3(0, -0.25, 0)},
                        {"wall_x+", Vec3(0.25, 1.5, 2.5), Vec3(2.75, 1.25, 0)},
                        {"wall_x-", Vec3(0.25, 1.5, 2.5), Vec3(-2.75, 1.25, 0)},
                        {"wall_z+", Vec3(2.5, 1.5, 0.25), Vec3(0, 1.25, 2.75)},
                        {"wall_z-", Vec3(2.5, 1.5, 0.25), Vec3(0, 1.25, -2.75)}};

ShapeSpec binShape(const BinPart& part, PileSpec::Floor floor, bool isFloor) {
  ShapeSpec s;
  s.name = part.name;
  if (floor == PileSpec::Floor::Plane && isFloor) {
    s.kind = ShapeSpec::Kind::Plane;  // y = 0 through the origin: the floor's top
  } else if (floor == PileSpec::Floor::Mesh) {
    s.kind = ShapeSpec::Kind::Generated;
    s.model = "box";
    s.halfExtents = part.half;
    s.triangles = 192;  // 4 subdivisions per edge: the tree has triangles to descend into
  } else {
    s.kind = ShapeSpec::Kind::Box;
    s.halfExtents = part.half;
  }
  return s;
}

std::vector<ShapeSpec> bodyShapes(const PileSpec& spec) {
  std::vector<ShapeSpec> shapes;
  if (spec.meshes.empty() && !spec.model.empty()) {
    ShapeSpec s;
    s.kind = ShapeSpec::Kind::Mesh;
    s.name = spec.model;
    // A catalogue model comes at its own size: scaled to the pile's, as a file's is.
    s.given = std::make_shared<const TriangleMesh>(gen::makeAnyModel(spec.model, spec.trianglesPerBody));
    s.size = kBodySize;
    shapes.push_back(std::move(s));
    return shapes;
  }
  if (spec.meshes.empty()) {
    for (TriangleMesh& mesh : generatedBodies(spec.trianglesPerBody)) {
      ShapeSpec s;
      s.kind = ShapeSpec::Kind::Mesh;
      s.name = mesh.name();
      s.given = std::make_shared<const TriangleMesh>(std::move(mesh));
      s.recentre = false;
      shapes.push_back(std::move(s));
    }
    return shapes;
  }
  for (std::size_t k = 0; k < spec.meshes.size(); ++k) {
    ShapeSpec s;
    s.kind = ShapeSpec::Kind::Mesh;
    s.name = spec.meshes[k].stem().string() + "#" + std::to_string(k);
    s.file = spec.meshes[k];
    s.size = kBodySize;
    shapes.push_back(std::move(s));
  }
  return shapes;
}

}  // namespace

Scene makePileScene(const PileSpec& spec) {
  if (spec.bodies <= 0) {
    throw std::invalid_argument("pile: bodies must be positive, got " + std::to_string(spec.bodies));
  }
  Scene scene;
  scene.description = std::to_string(spec.bodies) + " bodies dropped into a bin";
  scene.world.steps = spec.steps;
  Aabb inside;
  inside.lo = Vec3(-2.5, 0.0, -2.5);
  inside.hi = Vec3(2.5, kBoundsTop, 2.5);
  scene.world.bounds = inside;
  scene.effects.kind = Effects::Kind::Dynamics;
  scene.effects.friction = true;
  scene.effects.softContacts = true;
  scene.effects.sleeping = spec.sleeping;
  scene.view.given = true;
  // From above the near wall's rim, steep enough to see the floor's middle over it.
  scene.view.eye = Vec3(2.0, 7.5, 4.5);
  scene.view.target = Vec3(0.0, 0.2, 0.0);
  scene.view.fovDegrees = 45.0;

  bool first = true;
  for (const BinPart& part : kBin) {
    BodySpec b;
    b.kind = BodySpec::Kind::Static;
    b.name = part.name;
    b.shape = scene.shapes.size();
    b.friction = kFriction;
    const bool plane = spec.floor == PileSpec::Floor::Plane && first;
    if (!plane) b.pose.translation = part.centre;
    scene.shapes.push_back(binShape(part, spec.floor, first));
    scene.bodies.push_back(b);
    first = false;
  }

  const std::size_t firstBodyShape = scene.shapes.size();
  for (ShapeSpec& s : bodyShapes(spec)) scene.shapes.push_back(std::move(s));
  const std::size_t kinds = scene.shapes.size() - firstBodyShape;
  std::mt19937_64 rng(spec.seed);
  std::uniform_real_distribution<double> jitter(-0.1, 0.1);
  for (int i = 0; i < spec.bodies; ++i) {
    BodySpec b;
    b.kind = BodySpec::Kind::Dynamic;
    b.name = "body" + std::to_string(i);
    b.shape = firstBodyShape + static_cast<std::size_t>(i) % kinds;
    b.mass = 1.0;
    b.friction = kFriction;
    // The pose places the centre of mass, as the pile always has: bodies of any file start
    // on the grid, not offset by where their file's origin lies.
    b.poseOf = BodySpec::PoseOf::CentreOfMass;
    const int layer = i / 9, cell = i % 9;
    const Vec3 at(-0.9 + 0.9 * (cell % 3) + jitter(rng), 1.0 + 0.9 * layer,
                  -0.9 + 0.9 * (cell / 3) + jitter(rng));
    b.pose = Pose{randomRotation(rng).toRotationMatrix(), at};
    scene.bodies.push_back(b);
  }
  return scene;
}

}  // namespace adb::scene
