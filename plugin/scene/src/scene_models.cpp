#include "adb/scene/scene_models.h"

#include <algorithm>
#include <cmath>

#include "adb/support/mesh_generators.h"

namespace adb::scene {
namespace {

// A gear 1 across and 0.2 thick in the xy plane (axis z), teeth 0.08 deep. Two of them mesh
// without touching at rest as adb::gen::makeGearPair places them: centres 0.944 apart, the
// left one turned by -pi/teeth about z, the right one by pi.
TriangleMesh gearMesh(int teeth, std::size_t triangles) {
  // makeGear: 8 triangles per tooth and segment with one radial and one axial segment.
  const int perTooth = std::max(
      2, static_cast<int>(static_cast<double>(triangles) / (8.0 * std::max(teeth, 1))));
  return gen::makeGear(teeth, 0.5, 0.42, 0.1, 0.2, perTooth);
}

TriangleMesh boxMesh(const Vec3& halfExtents, std::size_t triangles) {
  // 12 s^2 triangles for s subdivisions per edge.
  const int s = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(triangles) / 12.0)));
  return gen::makeBox(halfExtents, s);
}

TriangleMesh scaled(const TriangleMesh& mesh, double scale) {
  if (scale == 1.0) return mesh;
  return gen::transformed(mesh, Pose{scale * Mat3::Identity(), Vec3::Zero()});
}

}  // namespace

std::vector<std::string> generatedModelNames() {
  std::vector<std::string> names = gen::modelNames();
  for (const std::string& name : gen::realMeshModelNames()) names.push_back(name);
  names.emplace_back("gear");
  names.emplace_back("box");
  return names;
}

TriangleMesh generatedMesh(const ShapeSpec& shape) {
  if (shape.model == "gear") return scaled(gearMesh(shape.teeth, shape.triangles), shape.scale);
  if (shape.model == "box") return scaled(boxMesh(shape.halfExtents, shape.triangles), shape.scale);
  // (A fixed model, "room" or "robot", ignores "triangles".)
  return scaled(gen::makeAnyModel(shape.model, shape.triangles), shape.scale);
}

}  // namespace adb::scene
