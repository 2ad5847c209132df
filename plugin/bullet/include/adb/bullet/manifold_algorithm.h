// ManifoldAlgorithm: what adb's Bullet collision algorithms share — which body is the mesh,
// one persistent manifold made on first use and released with the algorithm, no continuous
// collision detection — and CreateAlgorithm, the factory Bullet's dispatcher calls.
#pragma once

#include <BulletCollision/BroadphaseCollision/btDispatcher.h>
#include <BulletCollision/CollisionDispatch/btActivatingCollisionAlgorithm.h>
#include <BulletCollision/CollisionDispatch/btCollisionCreateFunc.h>

#include <new>

#include "adb/bullet/precision.h"

class btManifoldResult;

namespace adb {

class ManifoldAlgorithm : public btActivatingCollisionAlgorithm {
 public:
  /// `swapped`: body0 is the other shape and body1 the mesh.
  ManifoldAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
                    const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                    bool swapped)
      : btActivatingCollisionAlgorithm(ci, body0, body1), m_swapped(swapped) {}
  ~ManifoldAlgorithm() override {
    if (m_manifold) m_dispatcher->releaseManifold(m_manifold);
  }

  btScalar calculateTimeOfImpact(btCollisionObject*, btCollisionObject*, const btDispatcherInfo&,
                                 btManifoldResult*) override {
    return 1;  // no continuous collision detection against meshes
  }
  void getAllContactManifolds(btManifoldArray& manifolds) override {
    if (m_manifold) manifolds.push_back(m_manifold);
  }

 protected:
  /// Whether both bodies' poses are usable (adb/core/query.h, poseDefect). When one is not,
  /// the pair's manifold is emptied (its points would carry the bad pose into the solver)
  /// and the body is reported to an adb::Dispatcher: the caller skips the pair.
  bool acceptPoses(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1);
  /// The pair's manifold (made on first use), set as `result`'s.
  btPersistentManifold* manifoldFor(const btCollisionObjectWrapper* body0,
                                    const btCollisionObjectWrapper* body1,
                                    btManifoldResult* result);

  bool m_swapped;

 private:
  btPersistentManifold* m_manifold = nullptr;
};

/// The dispatcher's factory for an algorithm constructed as Algo(ci, body0, body1, swapped);
/// set m_swapped for the mesh-second order. Algorithms live in the dispatcher's pool.
template <class Algo>
struct CreateAlgorithm : public btCollisionAlgorithmCreateFunc {
  btCollisionAlgorithm* CreateCollisionAlgorithm(btCollisionAlgorithmConstructionInfo& ci,
                                                 const btCollisionObjectWrapper* body0,
                                                 const btCollisionObjectWrapper* body1) override {
    void* memory = ci.m_dispatcher1->allocateCollisionAlgorithm(sizeof(Algo));
    return new (memory) Algo(ci, body0, body1, m_swapped);
  }
};

}  // namespace adb
