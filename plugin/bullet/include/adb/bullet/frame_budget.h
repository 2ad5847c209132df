// FrameSettings and FrameStats: the per-step budget adb::Dispatcher spends on every pair
// that involves an adb mesh, the quality knobs of the pair queries and contacts, and what a
// step actually did.
//
// Policy (docs/bullet-budget.md has the measurements): pairs with a static body first, then
// the rest. Pairs that are not mesh-mesh (a mesh against a convex shape, a plane or another
// concave shape) run whole or not at all, those whose mesh moved most since they last ran
// first: those with a static body may take all that is left, the others an even share; one
// that does not fit keeps its last contacts (refreshed for the new poses). When the budget is
// smaller than every pair's expected cost, a pair with a static body whose mesh has barely
// moved keeps its contacts, and runs only on what the mesh-mesh pairs leave. One expected to
// cost more than the whole budget runs regardless (its estimate is only re-measured by
// running) every third step, or at once when its mesh has moved past the contact breaking
// threshold. Each mesh-mesh pair is given what it needed last step, at most an even share of
// what is left; then, while budget is left, the pairs whose contacts are least complete get
// as much again, resumed where they stopped. Mesh-mesh queries run in rounds whose grants
// are decided before any of them runs (FrameSettings::threads). Pairs with the world whose
// skipping could cost a body (arriving at it, sinking into it, slipping where it holds the body
// up, or approaching it) run whatever the budget, first. Mesh-box and mesh-plane contacts are
// sampled: each of 16 regions of the tree (4 under a binding budget) gives its deepest
// points (adb/core/box_query.h, forEachDeepestTriangleNear). A mesh-mesh pair is decided
// when its traversal completed (exact contacts, sampled per contact region) or reached the
// quality target (kMin node pairs above pMin, which needs the paper's best-first traversal;
// otherwise pairs run depth first). Pairs the budget cut get plausible contacts from their
// unresolved node pairs whose calibrated probability of holding a contact
// (adb::openPairProbability) is >= pAccept. A time budget holds
// back the contact writing still to come and a margin that follows the overshoot's peaks.
// With a node-pair budget, a step is reproducible bit for bit. Meshes inside
// btCompoundShapes are scheduled like any other.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>

#include "adb/core/query.h"  // PoseDefect, Pose
#include "adb/core/tree.h"

class btCollisionObject;

namespace adb {

struct FrameSettings {
  /// Wall-clock budget per step for all adb pairs, in microseconds; infinity for none.
  /// 0 is valid: every mesh-mesh pair gets its roots tested and no contact, the other pairs
  /// do not run and keep what contacts they had, except the pairs that run whatever the
  /// budget where cutting them could lose a body (FrameStats::mustRunPairs).
  double budgetMicros = std::numeric_limits<double>::infinity();
  /// Node pairs per step for all adb pairs (the other pairs count the tree nodes and
  /// triangles they visit): the reproducible budget. Every mesh-mesh pair's
  /// roots are always tested, so a step evaluates at most max(budget, pairs) node pairs, and
  /// what the pairs that run whatever the budget take (FrameStats::mustRunNodePairs).
  std::uint64_t budgetNodePairs = std::numeric_limits<std::uint64_t>::max();
  /// A node pair with probability above pMin counts towards kMin (the paper's collision pair).
  double pMin = 0.99;
  /// kMin > 0: pairs run the paper's best-first traversal and stop refining once kMin node
  /// pairs are above pMin (paper Fig. 3), with plausible contacts. 0 (the default) never
  /// stops on quality: pairs run depth first (4x cheaper for a pile's contacts) and are
  /// refined towards exact contacts as far as the budget allows, which resting contact needs.
  int kMin = 0;
  /// An unresolved node pair becomes a plausible contact when its calibrated probability
  /// that a triangle below one node meets a triangle below the other
  /// (adb::openPairProbability, adb/core/open_pair_estimate.h) is >= pAccept. Not the
  /// traversal's priority key (OpenPair::p): that orders the traversal and is no probability.
  double pAccept = 0.9;
  /// Plausible contacts per pair at most (the most probable first; the manifold keeps 4).
  int maxPlausibleContacts = 8;
  /// Soften plausible contacts by their probability p (as for pAccept) through the per-point
  /// ERP (p times
  /// Bullet's default 0.8) and CFM (softCfm * (1 - p) / (1 - pAccept)): an uncertain contact
  /// pushes less hard. Exact contacts are never softened.
  bool softenPlausible = true;
  double softCfm = 1e-3;
  /// Whether each mesh-mesh pair keeps the node pairs its last query evaluated and re-tests
  /// only those its bodies' motion may have changed (adb::QuerySettings::keepFront): the
  /// same contacts, for about a third of the node pairs on a settling pile. The walk costs
  /// more time per node pair than the descent it replaces (on the 50-body pile 1.08x the
  /// step time for 0.30x the node pairs, docs/bullet-budget.md), so by default fronts are
  /// kept where node pairs are what is budgeted.
  enum class Fronts {
    WithNodePairBudget,  ///< with a budgetNodePairs (the default)
    Always,
    Never,               ///< every query descends from the roots
  };
  Fronts fronts = Fronts::WithNodePairBudget;
  /// Threads for adb's pair work: 0 all hardware threads, 1 none (the default), N at most N
  /// (oneTBB's pool). Mesh-mesh queries and their contact points run in rounds of up to 16
  /// pairs whose grants are decided before any of them runs (without a budget, a group of
  /// pairs is one round); without a budget the pairs of a mesh with a plane, box, sphere or
  /// capsule gather their contacts on the pool too. Their bookkeeping and every contact
  /// written to Bullet happen on the thread that called stepSimulation, in pair order. So
  /// with or without a node-pair budget the simulation is the same bit for bit at any count.
  /// A time budget is wall-clock time, shared by the threads. Bullet's own work stays on the
  /// stepping thread.
  int threads = 1;
  /// Pairs whose bodies barely moved against each other since their contacts were made
  /// keep them, re-measured at the new poses, without colliding (FrameStats::reusedPairs):
  /// what lets a resting pile settle, sleep and cost little. Off only to measure what it
  /// does (docs/bullet-results.md, "Piles that fall asleep").
  bool keepRestingContacts = true;
  /// Audit each step's plausible contacts against the triangles (FrameStats::audit, and
  /// Dispatcher::lastAuditedContacts), after the step's contacts are written, at the poses
  /// they were made for; it writes nothing to the world, so the simulation is the same with
  /// it on (its time is FrameStats::audit.micros, not part of FrameStats::micros). Off by
  /// default: a measurement, it costs an exact query per cut pair and a brute-force test of
  /// every accepted plausible contact.
  bool auditContacts = false;
};

/// The largest FrameSettings::threads accepted.
inline constexpr int kMaxThreads = 256;

/// FrameSettings::Fronts' names in scene files and on adb-demo's command line, by value.
inline constexpr std::array<const char*, 3> kFrontsNames = {"node_pair_budget", "always",
                                                             "never"};
/// The Fronts named `name` (one of kFrontsNames), or nothing.
std::optional<FrameSettings::Fronts> frontsNamed(const std::string& name);

/// Throws SettingsError naming the first field out of range (Dispatcher::setFrameSettings
/// calls it, as adb::validate(QuerySettings) is called for queries).
void validate(const FrameSettings& settings);

/// A body whose pose adb could not use in a step: its adb pairs were skipped (no contacts,
/// its manifolds emptied) and the world went on.
struct BadPose {
  const btCollisionObject* body = nullptr;
  int bodyIndex = -1;           ///< btCollisionObject::getWorldArrayIndex()
  void* userPointer = nullptr;  ///< btCollisionObject::getUserPointer()
  /// NonFinite also for a rigid body whose velocities are not finite (its pose would be
  /// by the end of the step).
  PoseDefect defect = PoseDefect::None;
};

/// One mesh-mesh pair of the last step as the budget left it (Dispatcher::lastMeshPairs): which
/// pairs a budget cut, and how sure their answers are (to show them, or to act on them).
struct MeshPairReport {
  enum class Outcome {
    Exact,    ///< traversal completed: exact contacts
    Quality,  ///< stopped at the quality target (kMin node pairs above pMin)
    Cut,      ///< cut by the budget: plausible contacts where probable (pAccept)
  };
  const btCollisionObject* body0 = nullptr;
  const btCollisionObject* body1 = nullptr;
  Outcome outcome = Outcome::Exact;
  double confidence = 1.0;    ///< see FrameStats::meanConfidence
  double completeness = 1.0;  ///< see FrameStats::meanCompleteness
};

/// The audit of a step's plausible contacts (FrameSettings::auditContacts), over the
/// mesh-mesh pairs whose contacts were made from a query the budget cut (or that stopped at
/// the quality target): the pairs that got plausible contacts. Judged at the poses the
/// contacts were made for, against the triangles: an exact query of each pair (no budget,
/// every intersecting triangle pair, the pair's contact margin) and a brute-force test of
/// the triangles below each accepted plausible contact's two nodes.
struct ContactAuditStats {
  /// Triangle pairs an audit's exact query keeps per pair at most (QuerySettings::
  /// maxWitnesses): `exact` and `missed` count those; a pair with more counts in
  /// `cappedPairs`.
  static constexpr std::uint32_t kMaxExactPairs = 4096;
  bool on = false;               ///< the step was audited
  std::uint32_t pairs = 0;       ///< pairs audited
  /// Their accepted plausible contacts (the open pairs chosen, before the manifold's
  /// reduction): FrameStats::plausibleContacts of these pairs.
  std::uint32_t accepted = 0;
  /// Of those, ghosts: no triangle below one node comes within the pair's contact margin of
  /// a triangle below the other (for a pair without speculative contacts: none intersects),
  /// by brute force.
  std::uint32_t ghosts = 0;
  /// Of the ghosts, those whose triangles do not come within Bullet's contact breaking
  /// threshold of the pair's manifold either (nor the contact margin, if larger).
  std::uint32_t farGhosts = 0;
  /// Triangle pairs the exact query finds (intersecting, or within the contact margin), at
  /// most kMaxExactPairs per pair.
  std::uint64_t exact = 0;
  /// Of those, missed: neither found by the cut query (its exact witnesses) nor below an
  /// accepted plausible contact (its node pair holds both triangles).
  std::uint64_t missed = 0;
  /// Of the missed, those below an open pair the cut left unaccepted; the others lay where
  /// the cut query had been and its contact sampling (at most 4 triangle pairs per contact
  /// region, 64 per pair) passed them over.
  std::uint64_t missedOpen = 0;
  std::uint32_t cappedPairs = 0;  ///< pairs whose exact query found more than kMaxExactPairs
  double micros = 0.0;            ///< wall clock of the audit (not in FrameStats::micros)
};

/// One accepted plausible contact of the last step as the audit judged it
/// (Dispatcher::lastAuditedContacts): its node pair, the posed trees, and the verdicts.
struct AuditedContact {
  const btCollisionObject* body0 = nullptr;
  const btCollisionObject* body1 = nullptr;
  const AdbTree* treeA = nullptr;  ///< body 0's mesh's tree (a compound's child's)
  const AdbTree* treeB = nullptr;
  Pose poseA, poseB;               ///< the trees' poses the contact was made for
  std::uint32_t nodeA = 0, nodeB = 0;
  double probability = 0.0;        ///< openPairProbability
  double margin = 0.0;             ///< the pair's contact margin (0 without speculation)
  double threshold = 0.0;          ///< max(margin, the manifold's breaking threshold)
  bool ghost = false;              ///< nothing within `margin` (ContactAuditStats::ghosts)
  bool farGhost = false;           ///< nothing within `threshold` either
};

/// What the last step did with the adb pairs it met.
struct FrameStats {
  /// Bodies with a pose adb could not use this step (all counted, the first few named).
  static constexpr int kNamedBadPoses = 4;
  std::uint32_t badPoseBodies = 0;
  BadPose badPoses[kNamedBadPoses];

  std::uint32_t pairs = 0;          ///< mesh-mesh pairs whose boxes overlapped
  /// Of those, the ones whose bodies barely moved against each other since their contacts
  /// were made: they kept them, re-measured at the new poses, without a query (counted as
  /// decided exactly).
  std::uint32_t reusedPairs = 0;
  /// adb pairs that are not mesh-mesh (a mesh against a convex shape, a plane or another
  /// concave shape; compound children included): each runs whole or not at all.
  std::uint32_t otherPairs = 0;
  /// Of those, the ones the budget skipped: they keep their last contacts, refreshed for
  /// the new poses.
  std::uint32_t otherKeptPairs = 0;
  /// Of the other pairs, the ones at rest that kept their contacts without colliding (as
  /// reusedPairs), before any budget was spent.
  std::uint32_t otherReusedPairs = 0;
  /// Node pairs (and, for the other pairs, nodes and triangles visited) the step would
  /// need for exact contacts everywhere, from each pair's last complete run: the scale
  /// against which to set a node-pair budget.
  std::uint64_t neededNodePairs = 0;
  /// What exact contacts everywhere would need if every mesh-mesh pair descended from its
  /// trees' roots, as it would without the fronts pairs keep across steps
  /// (QuerySettings::keepFront): neededNodePairs with each mesh-mesh pair's from-roots cost
  /// in place of its walk's (adb::QueryResult::fromScratchNodePairs). Budget fractions are
  /// stated against it.
  std::uint64_t fromScratchNodePairs = 0;
  std::uint32_t exactPairs = 0;     ///< decided exactly: traversal completed
  std::uint32_t qualityPairs = 0;   ///< stopped at the quality target (k_min above p_min)
  std::uint32_t cutPairs = 0;       ///< cut by the budget: plausible contacts (pAccept)
  /// Of those, the ones a time budget left no time to write: they keep last step's contacts,
  /// refreshed for the new poses.
  std::uint32_t lateKeptPairs = 0;
  /// Mesh-mesh pairs run whatever the budget, where cutting them could lose a body: a body
  /// sweeping (asked for CCD, or thin and fast against the world) or landing, or a pair with
  /// the world cut for steps while its body closes in on it (overdue). A budget that holds
  /// otherwise may be overrun by what they cost.
  std::uint32_t mustRunPairs = 0;
  std::uint64_t mustRunNodePairs = 0;  ///< node pairs those pairs evaluated (in nodePairs)
  std::uint32_t queries = 0;        ///< pair queries run (a pair re-run counts again)
  std::uint64_t nodePairs = 0;      ///< node pairs evaluated, all queries of the step (the
                                    ///< other pairs' nodes and triangles included)
  std::uint64_t otherNodePairs = 0;  ///< of which the other pairs' (what the world's contacts
                                     ///< took from the budget)
  std::uint32_t exactContacts = 0;  ///< contact points from intersecting triangle pairs
  std::uint32_t plausibleContacts = 0;  ///< contact points from unresolved node pairs
  double micros = 0.0;              ///< wall clock of the step's pair work, contacts included
  double contactMicros = 0.0;       ///< of which writing contacts into Bullet's manifolds
                                    ///< (decided pairs at once, cut ones after the queries;
                                    ///< their points are computed with the queries, on the
                                    ///< pool's threads)
  /// Per pair, the probability that its collision answer (touching or not) is right: 1 when
  /// decided exactly or when a triangle pair was found to intersect; otherwise the
  /// traversal's fitted estimate (adb::QueryResult::confidence, calibrated:
  /// docs/probability-model.md). Low where a budget cut a pair before it found out whether
  /// its bodies touch.
  double meanConfidence = 1.0;
  double worstConfidence = 1.0;
  /// Per pair, how complete its contacts are: 1 when decided exactly; the quality answer's
  /// confidence when stopped on quality; otherwise 1 - min(1, sum of Pr[X >= 1] over its
  /// unresolved node pairs), a lower bound on the chance that no intersecting triangle pair
  /// is left unseen. Near 0 for a cut pair deep in contact (certainly touching, with more
  /// contacts unseen): the refinement goes to the least complete pair first.
  double meanCompleteness = 1.0;
  double worstCompleteness = 1.0;
  /// Threads the step's queries could use (FrameSettings::threads resolved), and of
  /// `micros` the wall clock of the queries run in parallel: micros - parallelMicros is the
  /// serial part of adb's work.
  std::uint32_t threads = 1;
  double parallelMicros = 0.0;
  /// Per thread (up to kReportedThreads), its time in the parallel queries: at best each is
  /// parallelMicros.
  static constexpr int kReportedThreads = 64;
  std::array<double, kReportedThreads> threadBusyMicros{};
  /// With FrameSettings::auditContacts, the audit of the step's plausible contacts.
  ContactAuditStats audit;
};

}  // namespace adb
