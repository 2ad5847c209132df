#include "scene_run/convex_peer.h"

#include <btBulletCollisionCommon.h>

#include <cstdio>

#include "adb/bullet/conversions.h"
#include "adb/bullet/mesh_shape.h"
#include "scene_run/convex_decomposition.h"

namespace adb::demo {
namespace {

// Bullet grows a btConvexHullShape outwards by its margin (0.04 by default: 5 % of a 0.8 body,
// which would keep bodies apart by a visible gap and hide penetration from the probe); 0.01
// is the margin GImpact's triangles get by default.
constexpr double kHullMargin = 0.01;

}  // namespace

std::string DecompositionReport::describe() const {
  std::string perMesh, volumes;
  for (std::size_t k = 0; k < hullsPerMesh.size(); ++k) {
    char ratio[32];
    std::snprintf(ratio, sizeof ratio, volumeRatio[k] > 0 ? "%.2f" : "n/a", volumeRatio[k]);
    perMesh += (k ? ", " : "") + std::to_string(hullsPerMesh[k]);
    volumes += (k ? ", " : "") + std::string(ratio);
  }
  char text[160];
  std::snprintf(text, sizeof text, "%zu hulls over %zu meshes (", hulls, hullsPerMesh.size());
  char tail[96];
  std::snprintf(tail, sizeof tail, "), prepared in %.2f s; hulls' volume / mesh volume: ", seconds);
  return text + perMesh + tail + volumes;
}

scene::ConvexShapeMaker convexShapeMaker(DecompositionReport& report) {
  return [&report](const MeshData& mesh) {
    const ConvexDecomposition parts = decompose(mesh.mesh);
    report.hullsPerMesh.push_back(parts.hulls.size());
    report.volumeRatio.push_back(mesh.mass.volume > 0 ? parts.hullVolume / mesh.mass.volume : 0.0);
    report.hulls += parts.hulls.size();
    report.seconds += parts.seconds;
    // The hulls as children of a compound, in the mesh data's frame: no child offset.
    std::vector<std::unique_ptr<btCollisionShape>> shapes;
    auto compound = std::make_unique<btCompoundShape>(true, static_cast<int>(parts.hulls.size()));
    for (const std::vector<Vec3>& hull : parts.hulls) {
      auto child = std::make_unique<btConvexHullShape>();
      for (const Vec3& v : hull) child->addPoint(toBt(v), false);
      child->recalcLocalAabb();
      child->setMargin(static_cast<btScalar>(kHullMargin));
      compound->addChildShape(btTransform::getIdentity(), child.get());
      shapes.push_back(std::move(child));
    }
    shapes.push_back(std::move(compound));
    return shapes;
  };
}

}  // namespace adb::demo
