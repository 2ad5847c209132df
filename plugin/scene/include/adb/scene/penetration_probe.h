// PenetrationProbe: how deep bodies really are in each other, measured from their geometry
// whatever any backend's contacts report. A backend's contact depths are its own estimates
// (a plausible contact's depth is a guess from node statistics, GImpact's includes margins),
// so comparing backends by them compares estimates; this probe measures every backend the
// same way.
//
// The measure: for two closed meshes A and B, the deepest vertex of B inside A, as its
// distance to A's surface (and the same with A and B swapped). A vertex is inside when rays
// from it cross A's surface an odd number of times (the majority of three skewed rays, so
// that a ray through an edge does not decide); its depth is its distance to the nearest
// triangle. Only vertices inside both bodies' world boxes are tested.
#pragma once

#include <cstddef>
#include <vector>

#include "adb/core/geometry.h"
#include "adb/core/tree.h"

namespace adb::scene {

/// One body as the probe sees it: its tree (for inside and distance tests) and the vertices
/// its triangles use, in mesh coordinates.
struct ProbeBody {
  const AdbTree* tree = nullptr;
  const std::vector<Vec3>* vertices = nullptr;
  Pose pose;
};

/// The deepest penetration between any two bodies.
struct PenetrationReport {
  double depth = 0.0;          ///< deepest vertex inside another body, distance to its surface
  double relative = 0.0;       ///< the same over the penetrated body's size (box diagonal)
  /// Each body's deepest penetration with any other, averaged over the bodies: how hard the
  /// pile as a whole is pressed into itself (the maximum is one pair's worst moment).
  double meanDepth = 0.0;
  std::size_t pairsTested = 0; ///< pairs whose world boxes overlapped
};

/// Whether `point` (tree-local coordinates: mesh minus tree.origin()) is inside the closed
/// mesh of `tree`.
bool insideMesh(const AdbTree& tree, const Vec3& point);
/// Distance from `point` (tree-local) to the nearest triangle of `tree`.
double distanceToMesh(const AdbTree& tree, const Vec3& point);
/// The deepest of `worldVertices` (another body's, in world coordinates) inside `a`, among
/// those in `region` (world).
double deepestVertexInside(const ProbeBody& a, const std::vector<Vec3>& worldVertices,
                           const Aabb& region);

/// Measures every pair of bodies whose world boxes overlap.
PenetrationReport measurePenetration(const std::vector<ProbeBody>& bodies);

}  // namespace adb::scene
