// Internal: FrameScheduler, which collects the adb pairs of a step while Bullet dispatches
// and then spends the step's budget across them (policy: adb/bullet/frame_budget.h).
#pragma once

#include <BulletCollision/BroadphaseCollision/btDispatcher.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "adb/bullet/frame_budget.h"
#include "adb/core/query.h"
#include "contact_audit.h"
#include "contact_selection.h"
#include "deferred_pair.h"
#include "frame_cost_model.h"
#include "worker_pool.h"

namespace adb::detail {

/// One query of a mesh-mesh pair: what it may spend and how it goes on. Made by name
/// (fresh, resumed), not from a row of flags.
struct QueryRequest {
  std::uint64_t grant = 0;  ///< node pairs
  double micros = 0.0;      ///< time cap: what is left of the step (infinite: none)
  bool resume = false;      ///< go on from where the pair's last query stopped
  /// Granted less than it wants: a new exact query then descends deepest first.
  bool starved = false;
  /// A pair that runs whatever the budget (FrameScheduler::sweeps, overdue): an exact query
  /// with no grant and no time cap.
  bool whole = false;

  /// A query from the roots; `starved` as above.
  static QueryRequest fresh(std::uint64_t grant, double micros, bool starved = false) {
    return QueryRequest{grant, micros, false, starved};
  }
  /// The pair's last query, given `grant` more.
  static QueryRequest resumed(std::uint64_t grant, double micros) {
    return QueryRequest{grant, micros, true, false};
  }
  /// A query from the roots that runs to its end whatever the budget.
  static QueryRequest unbounded() {
    return QueryRequest{~std::uint64_t{0}, HUGE_VAL, false, false, true};
  }
};

class FrameScheduler {
 public:
  /// Starts a step: pairs noted from now on are scheduled by run().
  void begin();
  bool collecting() const { return m_collecting; }
  /// Notes a pair during the dispatch.
  void defer(ManifoldAlgorithm* algorithm, const btCollisionObjectWrapper* body0,
             const btCollisionObjectWrapper* body1);
  /// Spends the budget across the noted pairs, writes their manifolds, ends the step.
  void run(const FrameSettings& settings, const btDispatcherInfo& info);
  const FrameStats& stats() const { return m_stats; }
  /// The last step's mesh-mesh pairs (Dispatcher::lastMeshPairs).
  void meshPairs(std::vector<MeshPairReport>& out) const;
  /// The last step's audited plausible contacts (FrameSettings::auditContacts; empty when
  /// off).
  const std::vector<AuditedContact>& auditedContacts() const { return m_audited; }
  /// Notes a body with an unusable pose for this step and, the first time this step, tells
  /// the callback.
  void noteBadPose(const btCollisionObject* body, PoseDefect defect);
  void setBadPoseCallback(std::function<void(const BadPose&)> callback) {
    m_badPoseCallback = std::move(callback);
  }
  /// Ends the collection without a run (the dispatch threw): later queries are answered at
  /// once again.
  void abandon() { m_collecting = false; }

 private:
  using Clock = std::chrono::steady_clock;

  void firstPass(const FrameSettings& settings);
  bool binding(const FrameSettings& settings) const;
  /// Whether the step that just ended reached the budget: it cut a mesh-mesh pair or left
  /// a pair unrun (kept its last contacts) for lack of budget.
  bool reachedBudget(const FrameSettings& settings) const;
  void refine(const FrameSettings& settings);
  void deferOrDrop(std::uint32_t index, std::uint64_t reserved);
  /// Collides a pair that is not refined (mesh against a convex shape, a plane or another
  /// concave shape) when its last cost fits in `share` node pairs and `microsShare`, or when
  /// it costs more than the whole budget and has waited kMaxSkippedSteps; false (not run)
  /// otherwise.
  bool runWhole(DeferredPair& pair, std::uint64_t share, double microsShare,
                const FrameSettings& settings);
  /// The whole pairs not run yet, in their order, while what is left covers them; with
  /// `resting`, also those that kept their contacts because their mesh barely moved.
  void runWholesLeft(const FrameSettings& settings, bool resting);
  /// Pairs at rest keep their contacts without colliding (before the budget is spent).
  void keepRestingContacts();
  /// Pairs the budget left unrun keep their last contacts, refreshed for the new poses.
  void keepSkipped();
  /// A step without a budget runs every whole pair: the closed-form ones (a mesh against a
  /// plane, box, sphere or capsule) gather their contacts on the pool first, and runWhole
  /// then only writes them, in the pairs' order.
  void gatherWholes(const FrameSettings& settings);
  void traverse(DeferredPair& pair, const QueryRequest& request, const FrameSettings& settings);
  std::uint64_t account(DeferredPair& pair, const QueryRequest& request);
  /// The first pass's mesh-mesh queries of one group (anchored or not), `waiting` pairs of
  /// the group not run yet, in rounds.
  void firstQueries(bool group, std::uint64_t waiting, const FrameSettings& settings);
  /// The first pass's rounds over the group's overdue pairs (all run whatever the budget),
  /// or over its others; `waiting`: how many of them.
  void queryRounds(bool group, bool overdue, std::uint64_t waiting, const FrameSettings& settings);
  /// Starts a round: an empty batch, whose queries stop by what is left of the step now.
  void beginRound(const FrameSettings& settings);
  /// Runs the traversals of the round's batch (m_batch, m_requests) on the pool; the caller
  /// then counts them in batch order on this thread.
  void runRound(const FrameSettings& settings);
  /// Computes the contact points of the pairs not written yet (those the budget cut), on the
  /// pool.
  void computeLateContacts(const FrameSettings& settings);
  /// job(i) for i in [0, jobs) on the pool, its time added to the step's statistics.
  template <class Job>
  void runOnPool(std::size_t jobs, Job& job);
  /// Whether a pair runs whatever the budget: it has speculative contacts, or had them
  /// within the last ManifoldAlgorithm::kLandingSteps steps (its body is landing).
  static bool sweeps(const DeferredPair& pair);
  /// Whether a mesh-mesh pair with the world has been cut for more than kMaxSkippedSteps
  /// steps (or was never decided) while its body closed in on the world by more than the
  /// breaking threshold: it runs first in its group, whatever the budget. Read once a step,
  /// before any query (DeferredPair::overdue).
  bool overdue(const DeferredPair& pair) const;
  /// Whether a whole pair's body is arriving: nothing to keep, moved, near last time.
  bool arriving(const DeferredPair& pair) const;
  /// Whether a pair with the world is losing its hold on its body (sinking into the world,
  /// or slipping where it holds the body up): it runs whatever the budget.
  static bool losingHold(const DeferredPair& pair);
  /// Whether a pair with the world has a body that moved past the breaking threshold since
  /// the pair last ran and was near it then, or never ran: it runs whatever the budget.
  static bool approaching(const DeferredPair& pair);
  /// The order whole pairs run in (DeferredPair::urgency): arriving, then sweeping (CCD or
  /// landing), losing their hold or approaching (all run whatever the budget, first), then
  /// the others.
  static constexpr std::uint8_t kArriving = 0, kMustRun = 1, kInTurn = 2;
  std::uint8_t urgency(const DeferredPair& pair) const;
  bool rests(const DeferredPair& pair) const;
  void runMustRunWholes(const FrameSettings& settings);
  /// Whether a pair with the world has a moving body that another pair with the world holds
  /// up (noteSupported()).
  bool supported(const DeferredPair& pair) const;
  void noteSupported();
  static std::uint64_t firstWanted(const DeferredPair& pair);
  void settle(DeferredPair& pair, const FrameSettings& settings);
  double writePair(DeferredPair& pair, const FrameSettings& settings);
  bool outOfTime(const FrameSettings& settings) const;
  /// Microseconds since the step's pair work began (safe from any thread).
  double elapsedMicros() const;
  void writeContacts(const FrameSettings& settings);
  /// FrameSettings::auditContacts: audits the pairs that got plausible contacts this step,
  /// once everything is written and timed.
  void auditContacts(const FrameSettings& settings);
  std::uint64_t nodePairsLeft(const FrameSettings& settings) const;
  /// Microseconds left of a time budget, less the margin and, with `holdBackWrites`, the
  /// expected cost of the mesh-mesh contacts still to write.
  double microsLeft(const FrameSettings& settings, bool holdBackWrites = true) const;
  /// An even share among `waiting` pairs of what is left once `reserved` node pairs
  /// (granted earlier in the round) are spent; `micros`: what is left of a time budget.
  std::uint64_t share(const FrameSettings& settings, std::uint64_t waiting,
                      std::uint64_t reserved, double micros) const;
  double timeShare(double micros, std::uint64_t waiting) const;

  std::vector<DeferredPair> m_pairs;   // mesh-mesh, refined (reused: no allocation)
  std::vector<DeferredPair> m_wholes;  // the others: run whole or not at all
  // Bodies the world holds up this step: the moving body of a pair with a static or
  // kinematic body whose contacts push it up (holdsUp). Sorted, for supported(). Reused: no
  // allocation.
  std::vector<const btCollisionObject*> m_supported;
  const btDispatcherInfo* m_info = nullptr;  // the dispatch's, during run()
  std::vector<std::uint32_t> m_order; // the refinement heap: indices into m_pairs
  std::vector<std::uint32_t> m_batch; // the pairs of a round: indices into m_pairs
  std::vector<std::uint32_t> m_deferred;  // pairs a round had no room for (deferOrDrop)
  std::vector<QueryRequest> m_requests;  // and their requests
  // Contacts of whole pairs gathered on the pool (DeferredPair::gathered indexes them): a
  // ContactSelection is 10 KB (float) or 20 KB (double), so they are kept and reused, not made per step.
  struct GatheredContacts {
    ContactSelection selection;
    std::uint64_t work = 0;
    double micros = 0.0;
  };
  std::vector<GatheredContacts> m_gathered;
  std::vector<DeferredPair*> m_gathering;  // the pairs of m_gathered, this step
  // A time budget's end for the round's queries, in microseconds since m_start (infinite:
  // none): each query's time cap is what is left of it when the query starts, so that the
  // budget is shared across the threads as wall-clock time.
  double m_roundDeadline = 0.0;
  WorkerPool m_pool;
  FrameStats m_stats;
  Clock::time_point m_start;
  // Measured costs: they turn a time budget into node-pair shares and hold back the
  // contact writing.
  FrameCostModel m_costs;
  // Pairs of this step not queried yet, and queried but neither decided nor written.
  std::size_t m_unqueried = 0;
  std::size_t m_undecided = 0;
  // This step's budget is smaller than its pairs' expected cost, and it was reached lately:
  // only then does the policy economise (reachedLately()).
  bool m_binding = false;
  // The budget was reached (a pair cut, or left unrun) in one of the last kReachedSteps
  // steps: only then do clock and cost estimates decide anything (shares of a time budget,
  // starved descents, resting pairs, coarse sampling). A budget never reached changes nothing.
  bool m_reachedLately = false;
  std::uint64_t m_lastReached = 0;  // the last step that reached the budget (0: none)
  bool m_collecting = false;
  std::uint64_t m_step = 0;  // steps begun
  // Bodies with unusable poses this step (reused: no allocation in steady state).
  std::vector<const btCollisionObject*> m_badBodies;
  std::function<void(const BadPose&)> m_badPoseCallback;
  // The audit (FrameSettings::auditContacts): made on the first audited step, so that a
  // world that never audits holds none of its buffers.
  std::unique_ptr<ContactAudit> m_audit;
  std::vector<AuditedContact> m_audited;
  std::uint32_t m_badNamed = 0;
  BadPose m_badNamedPoses[FrameStats::kNamedBadPoses];
};

}  // namespace adb::detail
