// The convex peer (adb-demo --backend convex): each moving mesh decomposed into convex hulls
// by Bullet's HACD (convex_decomposition.h), the hulls children of a btCompoundShape, in the
// mesh's principal frame (the same inertia and bin as every backend). What Bullet users
// prepare when they have no concave-concave algorithm.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "adb/scene/scene_world.h"

namespace adb::demo {

/// What the decompositions cost, over the distinct meshes of a run.
struct DecompositionReport {
  std::vector<std::size_t> hullsPerMesh;
  /// Per mesh, the hulls' summed volume over the mesh's (0 when the mesh is not closed and has
  /// no volume): how much the hulls fill that the body does not.
  std::vector<double> volumeRatio;
  std::size_t hulls = 0;
  double seconds = 0.0;  ///< the decompositions' wall clock
  /// One line: "12 hulls over 3 meshes (4, 5, 3), prepared in 1.9 s; hulls' volume / mesh
  /// volume: 1.21, 1.05, 1.33".
  std::string describe() const;
};

/// A shape maker for scene::Backend::Convex that adds what it decomposed to `report` (which
/// must outlive the world).
scene::ConvexShapeMaker convexShapeMaker(DecompositionReport& report);

}  // namespace adb::demo
