// MeshMeshAlgorithm: Bullet's collision algorithm for a pair of MeshShapes, and the one call
// that registers adb with a dispatcher.
//
// This first version answers each pair on its own with the tree's exact mode and turns the
// intersecting triangle pairs into contacts (adb/core/triangle_contact.h); the frame budget
// across all pairs and plausible contacts from probabilistic witnesses come next (issue 3).
#pragma once

#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>

#include "adb/bullet/manifold_algorithm.h"
#include "adb/core/query.h"

namespace adb {

class MeshMeshAlgorithm : public ManifoldAlgorithm {
 public:
  using ManifoldAlgorithm::ManifoldAlgorithm;

  void processCollision(const btCollisionObjectWrapper* body0,
                        const btCollisionObjectWrapper* body1, const btDispatcherInfo& info,
                        btManifoldResult* result) override;

 private:
  QueryScratch m_scratch;  // grows to this pair's largest query, then stays
};

/// Bytes a dispatcher's algorithm pool must hold per element for adb's algorithms: pass it
/// as btDefaultCollisionConstructionInfo::m_customCollisionAlgorithmMaxElementSize.
std::size_t algorithmPoolElementSize();

/// Bullet's construction info with the algorithm pool sized for adb: start a world's
/// btDefaultCollisionConfiguration from this (and change what else it needs).
btDefaultCollisionConstructionInfo collisionConstructionInfo();

/// Registers adb's algorithms with `dispatcher`, for contact points and for closest points (so
/// contactTest and contactPairTest work): MeshMeshAlgorithm for MeshShape pairs and
/// MeshConvexAlgorithm for a MeshShape against every convex shape type, MeshPlaneAlgorithm
/// against a static plane and MeshConcaveAlgorithm against every other concave shape (a
/// btBvhTriangleMeshShape ground, a heightfield), both orders. Compounds reach these through
/// Bullet's compound algorithm. Throws SettingsError when the configuration's algorithm pool is too small (see
/// algorithmPoolElementSize()).
void registerAlgorithms(btCollisionDispatcher& dispatcher,
                        btDefaultCollisionConfiguration& configuration);

}  // namespace adb
