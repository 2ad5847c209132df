// MeshConvexAlgorithm: a MeshShape against any convex shape (box, sphere, capsule, convex
// hull, ...), through the triangles of the mesh near the convex shape — Bullet's own
// convex-concave path, minus its SDF branch: Bullet treats CUSTOM_CONCAVE_SHAPE_TYPE as an
// SDF shape and would cast a MeshShape to btSdfCollisionShape.
#pragma once

#include <BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btConvexConcaveCollisionAlgorithm.h>

#include "adb/bullet/precision.h"

namespace adb {

ATTRIBUTE_ALIGNED16(class) MeshConvexAlgorithm : public btActivatingCollisionAlgorithm {
 public:
  BT_DECLARE_ALIGNED_ALLOCATOR();

  /// `swapped`: body0 is the mesh and body1 the convex shape.
  MeshConvexAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
                      const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                      bool swapped);

  void processCollision(const btCollisionObjectWrapper* body0,
                        const btCollisionObjectWrapper* body1, const btDispatcherInfo& info,
                        btManifoldResult* result) override;
  btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                 btManifoldResult*) override {
    return 1;  // no continuous collision detection against meshes
  }
  void getAllContactManifolds(btManifoldArray& manifolds) override;

 private:
  bool m_swapped;
  btConvexTriangleCallback m_triangles;  // owns the manifold, runs convex-triangle tests
};

}  // namespace adb
