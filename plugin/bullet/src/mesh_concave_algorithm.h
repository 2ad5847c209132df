// Internal: MeshConcaveAlgorithm, a MeshShape against another concave shape (a btBvhTriangleMeshShape
// ground, a heightfield, a GImpact mesh): each of the other shape's triangles near the mesh
// is tested against the mesh triangles the tree finds near it, exactly.
#pragma once

#include "manifold_algorithm.h"

namespace adb {

class MeshConcaveAlgorithm : public ManifoldAlgorithm {
 public:
  using ManifoldAlgorithm::ManifoldAlgorithm;

  std::uint64_t collideNow(const btCollisionObjectWrapper* body0,
                           const btCollisionObjectWrapper* body1, const btDispatcherInfo& info,
                           btManifoldResult* result) override;
};

}  // namespace adb
