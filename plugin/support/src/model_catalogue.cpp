// The named models: the benchmark's, each picking its parameters from a target triangle count,
// and the real-mesh ones ("slivers" from a target; "room" and "robot" at one resolution).
#include "adb/support/mesh_generators.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "generator_kit.h"

namespace adb::gen {
using namespace kit;  // the generators' shared parts
namespace {

// Named models: each picks its parameters from the target count (closed form where a free
// parameter can absorb the rounding, a scan over resolutions for the lock).

int roundedAtLeast(double value, int minimum) {
  return std::max(minimum, static_cast<int>(std::lround(value)));
}

TriangleMesh sphereModel(double target) {
  return makeSphere(0.8, roundedAtLeast(std::sqrt(target / 20.0), 2));
}

TriangleMesh torusModel(double target) {
  // 3 major per minor segment keeps the quads near square for radii 0.6 / 0.25.
  const int minor = roundedAtLeast(std::sqrt(target / 6.0), 3);
  return makeTorus(0.6, 0.25, roundedAtLeast(target / (2.0 * minor), 3), minor);
}

TriangleMesh knotModel(double target) {
  constexpr double kRadius = 0.55, kTube = 0.09;
  const double aspect = torusKnotLength(2, 3, kRadius) / (2.0 * kPi * kTube);
  const int around = roundedAtLeast(std::sqrt(target / (2.0 * aspect)), 6);
  return makeTorusKnot(2, 3, kRadius, kTube, roundedAtLeast(target / (2.0 * around), 12), around);
}

TriangleMesh gearsModel(double target) {
  // Pair of 12-tooth gears: 192 * segmentsPerTooth * layers triangles. Flooring the layer count
  // keeps segmentsPerTooth >= 4 * layers, so its rounding costs at most 12.5 %.
  const int layers = std::max(1, static_cast<int>(std::sqrt(target / 768.0)));
  const int perTooth = roundedAtLeast(target / (192.0 * layers), 4);
  return makeGearPair(12, 0.5, 0.4, 0.15, 0.25, perTooth, layers, layers);
}

TriangleMesh pipesModel(double target) {
  constexpr int kPipes = 6;
  constexpr double kLength = 1.6, kRadius = 0.08;
  const double aspect = kLength / (2.0 * kPi * kRadius);
  const int around = roundedAtLeast(std::sqrt(target / (4.0 * kPipes * aspect)), 8);
  const int rings = roundedAtLeast(target / (4.0 * kPipes * around), 2);
  return makePipeBundle(kPipes, kLength, kRadius, 0.02, around, rings - 1);
}

TriangleMesh lockModel(double target) {
  int best = 1;
  for (int r = 1; r < 4096; ++r) {
    const double count = lockTriangleCount(r);
    if (std::abs(std::log(count / target)) < std::abs(std::log(lockTriangleCount(best) / target))) {
      best = r;
    }
    if (count > 2.0 * target) break;
  }
  return makeLockAssembly(best);
}

// A sliver cylinder whose side triangles stay about 100:1 at every target (FCL's env.obj has a
// median of 125:1): with s segments and k rows, 2 s (k + 1) - 4 triangles and a side aspect
// of about (h / k) / (2 pi r / s) = h target / (4 pi r k (k + 1)), so k (k + 1) is chosen
// from the target and s absorbs the rounding.
TriangleMesh sliversModel(double target) {
  constexpr double kRadius = 0.25, kHeight = 1.8, kSideAspect = 100.0;
  const double rowProduct = kHeight * target / (4.0 * kPi * kRadius * kSideAspect);
  const int rows = roundedAtLeast(0.5 * (std::sqrt(1.0 + 4.0 * rowProduct) - 1.0), 1);
  const int segments = roundedAtLeast((target + 4.0) / (2.0 * (rows + 1)), 3);
  return makeSliverCylinder(kRadius, kHeight, segments, rows);
}

struct NamedModel {
  const char* name;
  TriangleMesh (*make)(double target);
};

// modelNames(): the benchmark's shapes.
constexpr std::array<NamedModel, 6> kModels = {{
    {"pipes", pipesModel},
    {"gears", gearsModel},
    {"lock", lockModel},
    {"knot", knotModel},
    {"torus", torusModel},
    {"sphere", sphereModel},
}};

// Real meshes' triangles, following a target: makeModel builds them too.
constexpr std::array<NamedModel, 1> kRealMeshModels = {{
    {"slivers", sliversModel},
}};

struct FixedModel {
  const char* name;
  TriangleMesh (*make)();
};

constexpr std::array<FixedModel, 2> kFixedModels = {{
    {"room", makeRoom},
    {"robot", makeRobotArm},
}};

template <typename Table>
std::string joinedNames(const Table& table) {
  std::string names;
  for (const auto& m : table) names += (names.empty() ? "" : ", ") + std::string(m.name);
  return names;
}

// TriangleMesh has no setter for its name; a model is renamed by copying (once per makeModel).
TriangleMesh named(const TriangleMesh& mesh, const std::string& name) {
  return TriangleMesh(mesh.vertices(), mesh.triangles(), name);
}

}  // namespace

std::vector<std::string> modelNames() {
  std::vector<std::string> names;
  for (const NamedModel& m : kModels) names.emplace_back(m.name);
  return names;
}

std::vector<std::string> realMeshModelNames() {
  std::vector<std::string> names;
  for (const NamedModel& m : kRealMeshModels) names.emplace_back(m.name);
  for (const FixedModel& m : kFixedModels) names.emplace_back(m.name);
  return names;
}

std::vector<std::string> fixedModelNames() {
  std::vector<std::string> names;
  for (const FixedModel& m : kFixedModels) names.emplace_back(m.name);
  return names;
}

TriangleMesh makeModel(const std::string& name, std::size_t targetTriangles) {
  const double target = std::max(1.0, static_cast<double>(targetTriangles));
  for (const NamedModel& m : kModels) {
    if (name == m.name) return named(m.make(target), name);
  }
  for (const NamedModel& m : kRealMeshModels) {
    if (name == m.name) return named(m.make(target), name);
  }
  for (const FixedModel& m : kFixedModels) {
    if (name == m.name) {
      throw MeshError("makeModel: \"" + name +
                      "\" has one fixed resolution, not a target triangle count: "
                      "build it with makeFixedModel");
    }
  }
  throw MeshError("makeModel: unknown model name \"" + name + "\"; known models: " +
                  joinedNames(kModels) + ", " + joinedNames(kRealMeshModels));
}

TriangleMesh makeFixedModel(const std::string& name) {
  for (const FixedModel& m : kFixedModels) {
    if (name == m.name) return named(m.make(), name);
  }
  throw MeshError("makeFixedModel: unknown model name \"" + name + "\"; known fixed models: " +
                  joinedNames(kFixedModels));
}

TriangleMesh makeAnyModel(const std::string& name, std::size_t targetTriangles) {
  const std::vector<std::string> fixed = fixedModelNames();
  if (std::find(fixed.begin(), fixed.end(), name) != fixed.end()) return makeFixedModel(name);
  return makeModel(name, targetTriangles);
}

}  // namespace adb::gen
