// Internal: MeshMeshAlgorithm, Bullet's collision algorithm for a pair of MeshShapes.
//
// Under adb::Dispatcher the pair is handed to the step's scheduler, which queries it within
// the step's budget (adb/bullet/frame_budget.h), refining it while budget is left, and then
// has it write its contacts: exact ones from intersecting triangle pairs, plausible ones
// from node pairs the budget left unresolved. Elsewhere (a plain btCollisionDispatcher,
// contactTest/contactPairTest) the pair is answered at once in exact mode.
#pragma once

#include <BulletCollision/CollisionShapes/btCollisionShape.h>
#include <LinearMath/btTransform.h>

#include <cstdint>
#include <vector>

#include "adb/bullet/frame_budget.h"
#include "adb/core/query.h"
#include "manifold_algorithm.h"
#include "pair_contacts.h"

namespace adb {

namespace detail {
struct DeferredPair;
}  // namespace detail

/// Contact points one pair wrote in a step.
struct ContactCount {
  std::uint32_t exact = 0;
  std::uint32_t plausible = 0;
};

class MeshMeshAlgorithm : public ManifoldAlgorithm {
 public:
  using ManifoldAlgorithm::ManifoldAlgorithm;

  /// At once, exact (a plain dispatcher, contactTest).
  std::uint64_t collideNow(const btCollisionObjectWrapper* body0,
                           const btCollisionObjectWrapper* body1, const btDispatcherInfo& info,
                           btManifoldResult* result) override;
  bool refinable() const override { return true; }

  // --- used by the scheduler -------------------------------------------------------------
  /// Starts the deferred pair's query with `settings` (or, with `resume`, continues the one
  /// a budget cut) and runs it within `budget`; the evidence stays in this pair's traversal.
  const QueryResult& query(const detail::DeferredPair& pair, const QuerySettings& settings,
                           const StepBudget& budget, bool resume);
  /// The result of the last call to query() (all its steps).
  const QueryResult& result() const { return m_traversal.result(); }
  /// The work of the last call to query().
  const StepWork& lastStep() const { return m_traversal.lastStep(); }
  /// Computes the contact points of the last query: geometry that reads only this pair's
  /// trees, traversal and manifold, so that the queries' jobs may run it on any thread.
  void computeContacts(const detail::DeferredPair& pair, const FrameSettings& settings);
  /// Writes the contacts of the last query into the pair's manifold (computing them first if
  /// computeContacts has not since the query): the stepping thread's part.
  ContactCount writeContacts(const detail::DeferredPair& pair, const FrameSettings& settings);
  /// Whether the budget cut the pair's last query (until this step's first query: last
  /// step's).
  bool cut() const { return isBudgetStop(m_lastStop); }
  /// Node pairs the last query that finished needed: the next step's first grant.
  std::uint64_t needed() const { return m_needed; }
  /// What needed() would be for a descent from the roots (QueryResult::fromScratchNodePairs).
  std::uint64_t neededFromScratch() const { return m_neededFromScratch; }
  /// The node pairs the last query left unresolved (empty when it completed).
  const std::vector<OpenPair>& openPairs() const { return m_traversal.openPairs(); }

  /// The triangle pairs the last query found (its exact witnesses).
  const std::vector<Witness>& witnesses() const { return m_traversal.witnesses(); }
  /// The queries' contact margin this step: 0, or for a pair with speculative contacts,
  /// Bullet's threshold plus the speculative reach.
  double contactMargin() const;

 private:
  // Resets the traversal for a new query; false (and an empty traversal) for a bad pose.
  bool start(const AdbTree& tree0, const btTransform& transform0, const AdbTree& tree1,
             const btTransform& transform1, const QuerySettings& settings);
  /// The contact points of the last query for bodies posed at `transform0` and `transform1`
  /// into m_points.
  void computePoints(const btCollisionShape* shape0, const btTransform& transform0,
                     const btCollisionShape* shape1, const btTransform& transform1,
                     const FrameSettings& settings);
  /// Writes m_points through `result` into the pair's manifold.
  ContactCount writePoints(const btCollisionObjectWrapper* body0,
                           const btCollisionObjectWrapper* body1, btManifoldResult& result);

  // The small members last, together, so that they share one padded word: the algorithm
  // must fit Bullet's default pool element (algorithmPoolElementSize).
  Traversal m_traversal;  // grows to this pair's largest query, then stays
  std::uint64_t m_needed = 0;
  std::uint64_t m_neededFromScratch = 0;
  detail::ContactPoints m_points;  // the last query's contact points, until written
  ContactCount m_pointCount;
  StopReason m_lastStop = StopReason::Completed;  // why the last query stopped
  bool m_pointsReady = false;  // m_points are the last query's
};

}  // namespace adb
