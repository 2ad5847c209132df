// Internal: MeshPlaneAlgorithm, a MeshShape against a btStaticPlaneShape (a ground plane): the vertices
// of the mesh below or near the plane, found through the tree, become contacts.
#pragma once

#include "manifold_algorithm.h"

namespace adb {

class MeshPlaneAlgorithm : public ManifoldAlgorithm {
 public:
  using ManifoldAlgorithm::ManifoldAlgorithm;

  std::uint64_t collideNow(const btCollisionObjectWrapper* body0,
                           const btCollisionObjectWrapper* body1, const btDispatcherInfo& info,
                           btManifoldResult* result) override;
  /// Always: a plane is closed form.
  bool gathersOffThread(const btCollisionObjectWrapper* body0,
                        const btCollisionObjectWrapper* body1) const override;
  std::uint64_t gather(const btCollisionObjectWrapper* body0,
                       const btCollisionObjectWrapper* body1, btScalar closestPoints,
                       detail::ContactSelection& selection) const override;
};

}  // namespace adb
