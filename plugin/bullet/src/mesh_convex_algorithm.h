// Internal: MeshConvexAlgorithm, a MeshShape against a convex shape. The tree is culled with the convex
// shape's own oriented bounds taken into the mesh frame (its axis-aligned box there would
// cover the whole mesh for a tilted wall); spheres, capsules and boxes are then tested
// against each triangle in closed form (adb/core/primitive_contact.h), and every other
// convex shape (cylinder, cone, hull, ...) by Bullet's GJK/EPA per triangle. The candidate
// points are reduced to the deepest and the widest support before they reach the manifold.
#pragma once

#include "manifold_algorithm.h"

namespace adb {

class MeshConvexAlgorithm : public ManifoldAlgorithm {
 public:
  using ManifoldAlgorithm::ManifoldAlgorithm;

  std::uint64_t collideNow(const btCollisionObjectWrapper* body0,
                           const btCollisionObjectWrapper* body1, const btDispatcherInfo& info,
                           btManifoldResult* result) override;
  /// For spheres, capsules and boxes (closed form); GJK/EPA pairs stay on the stepping
  /// thread (Bullet's detectors, and the dispatcher's).
  bool gathersOffThread(const btCollisionObjectWrapper* body0,
                        const btCollisionObjectWrapper* body1) const override;
  std::uint64_t gather(const btCollisionObjectWrapper* body0,
                       const btCollisionObjectWrapper* body1, btScalar closestPoints,
                       detail::ContactSelection& selection) const override;

 private:
  /// How far apart candidates may be: the manifold's breaking threshold (or the result's
  /// closest-point threshold, if larger) and this step's speculative reach.
  double candidateThreshold(btScalar closestPoints) const;
};

}  // namespace adb
