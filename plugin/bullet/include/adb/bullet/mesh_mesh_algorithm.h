// MeshMeshAlgorithm: Bullet's collision algorithm for a pair of MeshShapes, and the one call
// that registers adb with a dispatcher.
//
// Under adb::Dispatcher the pair is handed to the step's scheduler, which queries it within
// the step's budget (adb/bullet/frame_budget.h) and then has it write its contacts: exact
// ones from intersecting triangle pairs, plausible ones from node pairs the budget left
// unresolved. Elsewhere (a plain btCollisionDispatcher, contactTest/contactPairTest, a mesh
// inside a compound) the pair is answered at once in exact mode.
#pragma once

#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>

#include <cstdint>
#include <vector>

#include "adb/bullet/frame_budget.h"
#include "adb/bullet/manifold_algorithm.h"
#include "adb/core/query.h"

namespace adb {

namespace detail {
class FrameScheduler;
struct DeferredPair;
}  // namespace detail

/// Contact points one pair wrote in a step.
struct ContactCount {
  std::uint32_t exact = 0;
  std::uint32_t plausible = 0;
};

class MeshMeshAlgorithm : public ManifoldAlgorithm {
 public:
  MeshMeshAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
                    const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                    bool swapped);

  void processCollision(const btCollisionObjectWrapper* body0,
                        const btCollisionObjectWrapper* body1, const btDispatcherInfo& info,
                        btManifoldResult* result) override;

  // --- used by the scheduler -------------------------------------------------------------
  /// Starts the deferred pair's query with `settings` (or, with `resume`, continues the one
  /// a budget cut) and runs it within `budget`; the evidence stays in this pair's traversal.
  const QueryResult& query(const detail::DeferredPair& pair, const QuerySettings& settings,
                           const StepBudget& budget, bool resume);
  /// The work of the last call to query().
  const StepWork& lastStep() const { return m_traversal.lastStep(); }
  /// Writes the contacts of the last query into the pair's manifold.
  ContactCount writeContacts(const detail::DeferredPair& pair, const FrameSettings& settings);
  /// Node pairs the last query that finished needed: the next step's first grant.
  std::uint64_t needed() const { return m_needed; }
  /// The node pairs the last query left unresolved (empty when it completed).
  const std::vector<OpenPair>& openPairs() const { return m_traversal.openPairs(); }

 private:
  // Resets the traversal for a new query; false (and an empty traversal) for a bad pose.
  bool start(const AdbTree& tree0, const btTransform& transform0, const AdbTree& tree1,
             const btTransform& transform1, const QuerySettings& settings);
  ContactCount addContacts(const btCollisionObjectWrapper* body0,
                           const btCollisionObjectWrapper* body1, btManifoldResult& result,
                           const FrameSettings& settings);

  Traversal m_traversal;  // grows to this pair's largest query, then stays
  StopReason m_lastStop = StopReason::Completed;  // why the last query stopped
  detail::FrameScheduler* m_scheduler = nullptr;  // set under adb::Dispatcher
  std::uint64_t m_needed = 0;
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
