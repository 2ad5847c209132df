// ConvexDecomposition: a concave body as a set of convex hulls, the way a Bullet user without
// a concave-concave algorithm makes one collide: Bullet's own HACD (Khaled Mamou's
// hierarchical approximate convex decomposition, shipped in Bullet's Extras and in Debian's
// libbullet-extras-dev), its hulls then become btConvexHullShape children of a
// btCompoundShape. The demo's `--backend convex` peer.
#pragma once

#include <cstddef>
#include <vector>

#include "adb/core/mesh.h"

namespace adb::demo {

/// HACD's knobs, at the values of Bullet's own HACD demo (ConvexDecompositionDemo) unless
/// the comment says otherwise.
struct DecompositionSettings {
  /// Largest concavity a cluster may have, in HACD's units: the mesh is scaled so that its
  /// bounding-box diagonal is 2000, so 100 allows a dent of 5 % of the body's diagonal.
  double concavity = 100.0;
  std::size_t minClusters = 2;       ///< HACD stops merging at this many clusters
  std::size_t maxHullVertices = 100;  ///< per hull (HACD simplifies larger hulls)
  double compacityWeight = 0.1;       ///< favours round clusters over long thin ones
  double volumeWeight = 0.0;
  /// Measure concavity at face centres too, not only at vertices. On by our choice (Bullet's
  /// demo has it off): an extruded body such as the generated gear has every vertex on its
  /// caps' rims, so at vertices alone every cluster looks convex and HACD merged the gear,
  /// bore and all, into 2 hulls (and took minutes doing it).
  bool facePoints = true;
};

/// The hulls of one mesh, in the mesh's own coordinates.
struct ConvexDecomposition {
  std::vector<std::vector<Vec3>> hulls;  ///< each hull's vertices
  /// The hulls' volumes added up (where hulls overlap, counted twice): against the mesh's own
  /// volume, how much space the hulls fill that the body does not (a torus's hole, a gear's gaps).
  double hullVolume = 0.0;
  double seconds = 0.0;                  ///< wall clock of the decomposition
};

/// Decomposes `mesh` (its triangles must share vertices: HACD finds neighbours by shared
/// edges). Throws std::runtime_error when HACD fails or returns no hull.
ConvexDecomposition decompose(const TriangleMesh& mesh, const DecompositionSettings& settings = {});

}  // namespace adb::demo
