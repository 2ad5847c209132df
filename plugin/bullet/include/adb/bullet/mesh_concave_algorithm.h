// MeshConcaveAlgorithm: a MeshShape against another concave shape (a btBvhTriangleMeshShape
// ground, a heightfield, a GImpact mesh): each of the other shape's triangles near the mesh
// is tested against the mesh triangles the tree finds near it, exactly.
#pragma once

#include <BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btCollisionCreateFunc.h>

#include "adb/bullet/precision.h"

namespace adb {

class MeshConcaveAlgorithm : public btActivatingCollisionAlgorithm {
 public:
  /// `swapped`: body0 is the other concave shape and body1 the mesh.
  MeshConcaveAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
                       const btCollisionObjectWrapper* body0,
                       const btCollisionObjectWrapper* body1, bool swapped);
  ~MeshConcaveAlgorithm() override;

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
