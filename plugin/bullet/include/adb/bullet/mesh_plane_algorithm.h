// MeshPlaneAlgorithm: a MeshShape against a btStaticPlaneShape (a ground plane): the vertices
// of the mesh below or near the plane, found through the tree, become contacts.
#pragma once

#include <BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btCollisionCreateFunc.h>

#include "adb/bullet/precision.h"

namespace adb {

class MeshPlaneAlgorithm : public btActivatingCollisionAlgorithm {
 public:
  /// `swapped`: body0 is the plane and body1 the mesh.
  MeshPlaneAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
                     const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                     bool swapped);
  ~MeshPlaneAlgorithm() override;

  void processCollision(const btCollisionObjectWrapper* body0,
                        const btCollisionObjectWrapper* body1, const btDispatcherInfo& info,
                        btManifoldResult* result) override;
  btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                 btManifoldResult*) override {
    return 1;  // no continuous collision detection against meshes
  }
  void getAllContactManifolds(btManifoldArray& manifolds) override;

  struct CreateFunc : public btCollisionAlgorithmCreateFunc {
    btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                   const btCollisionObjectWrapper* body0,
                                                   const btCollisionObjectWrapper* body1) override;
  };

 private:
  bool m_swapped;
  btPersistentManifold* m_manifold = nullptr;
};

}  // namespace adb
