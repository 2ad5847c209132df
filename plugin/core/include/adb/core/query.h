// Collision queries between two posed ADB-trees: the paper's probability-guided traversal
// (Fig. 3) with a quality target (p_min, k_min), a wall-clock and a work budget, and an exact
// mode that descends to triangle pairs.
//
// A query is a const function of two built trees: any number of threads may query the same
// trees at once, each with its own QueryScratch or Traversal. After either has grown to a
// query's size, repeating queries of that size allocates nothing.
//
// collide() runs one query to its end or its budget. A Traversal runs the same query in
// steps, keeping its frontier between them: a caller that shares one budget across many
// pairs (a physics step) refines the least certain pair without redoing any work.
#pragma once

#include <cstdint>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include "adb/core/collision_estimate.h"
#include "adb/core/errors.h"
#include "adb/core/geometry.h"
#include "adb/core/tree.h"

namespace adb {

enum class QueryMode {
  Adb,    ///< the paper's traversal: stop at k_min pairs with p > p_min, prune p = 0
  Exact,  ///< every overlapping pair down to triangle pairs; confidence 1 when it completes
};

/// Why a query stopped. Nothing is cut silently: a budget stop says so.
enum class StopReason {
  Completed,       ///< the traversal ran out of pairs: the answer is final under the mode
  QualityReached,  ///< ADB: k_min collision pairs found (paper Fig. 3)
  ExactHit,        ///< a triangle pair intersects (with stopAtFirstHit): certain
  TimeBudget,      ///< the wall-clock budget ran out
  WorkBudget,      ///< the node-pair budget ran out
  /// maxWitnesses intersecting triangle pairs are held (with stopWhenWitnessesFull): a
  /// collision, certain, and every further hit would be dropped.
  WitnessesFull,
};

const char* toString(StopReason r);
/// Whether a query stopped on a budget (cut: it may be resumed), not on an answer.
bool isBudgetStop(StopReason r);

/// Exact mode: the order in which the overlapping children of a node pair are descended.
enum class ExactDescent {
  /// Deepest box overlap first when the query has a budget, the trees' order otherwise.
  Auto,
  /// The trees' order, budget or not: a budget that never cuts the query changes nothing,
  /// and a resting contact samples the same triangle pairs step after step.
  TreeOrder,
  /// The deepest box overlap (the smallest overlap over the six face axes) first: a budget
  /// that cuts the descent has then seen the deepest contacts, the ones that keep bodies
  /// apart.
  DeepestFirst,
  /// The child pair with the most expected collision cells (the model's E[X]) first: with
  /// stopAtFirstHit, 21 to 34 % fewer node pairs than the trees' order on the generated models
  /// (what a node-pair budget counts), about the same time, as the cell counts cost what the
  /// pairs save (docs/core-results.md). Keeps no front (keepFront is ignored).
  MostCellsFirst,
};

/// ADB mode: what orders the queue of node pairs.
enum class AdbKey {
  /// A table that approximates Eq. 3 by the pair's expected collision cells and its depth term,
  /// in a bucket queue: a few operations a pair. Acceptance (p > pMin) still evaluates Eq. 3
  /// where a cheap bound says it could pass, so it accepts what Eq3 accepts.
  Table,
  /// Eq. 3 itself, evaluated for every pair, in a binary heap: the paper's order, kept to
  /// separate what the order changes from what the cost changes.
  Eq3,
};

struct QuerySettings {
  QueryMode mode = QueryMode::Adb;
  /// A node pair with probability above pMin is a collision pair (paper: 0.5, 0.9, 0.99).
  double pMin = 0.99;
  /// Report "collision" once kMin collision pairs were found (paper: 1, 5, 10).
  int kMin = 10;
  /// A node pair is a collision pair only when each of its nodes holds at least this many
  /// triangles and they are not slivers (kSliverFatness) (0..127; 0: the paper, every inner
  /// pair). The probability model reads a node's surface as many small polygons spread over
  /// its cells; a few large or long thin triangles are not that, and pairs of them were
  /// accepted where the triangles pass each other (a 384-triangle pipe bundle and a 20k
  /// cylinder of 100:1 slivers answer wrongly under the paper's rule and never with this:
  /// tests MeshesAsTheyCome.*, docs/probability-model.md section 7). Below it the traversal
  /// goes on to the triangles, which is cheap that near the leaves.
  int minTrianglesToAccept = 64;
  /// Wall-clock budget in microseconds; infinity for none. 0 is valid: the roots only.
  double budgetMicros = std::numeric_limits<double>::infinity();
  /// Node pairs that may be evaluated (box test + probability); the reproducible budget.
  /// The roots' own test is always made: nodePairs <= max(1, budgetNodePairs).
  std::uint64_t budgetNodePairs = std::numeric_limits<std::uint64_t>::max();
  /// Exact mode (and leaf pairs in ADB mode): stop at the first intersecting triangle pair.
  /// Off to collect every intersecting pair as witnesses (contact generation).
  bool stopAtFirstHit = true;
  /// Witnesses kept at most; more are counted in QueryResult::witnessesDropped.
  std::uint32_t maxWitnesses = 64;
  /// Stop once maxWitnesses intersecting triangle pairs are held (StopReason::WitnessesFull)
  /// instead of going on to count hits that would be dropped. For contact generation, whose
  /// contacts come from the witnesses: the same witnesses as the whole query, in the same
  /// order, for less work. `collides` is certain either way.
  bool stopWhenWitnessesFull = false;
  /// ADB mode: drop pairs whose boxes overlap but whose probability is 0 (the paper's rule).
  /// Off (the default), they are queued last instead, so a traversal that completes has tested
  /// every overlapping triangle pair (an exact answer, visited most likely first) and a cut
  /// one leaves them in QueryScratch::openPairs(). Pairs whose triangles' cells do not meet
  /// are dropped either way, as a proof (AdbTree::occupancy()). The rule was the main source
  /// of wrong "no" answers, most with confidence >= 0.99 on meshes of slivers (a cell crossed
  /// by slivers holds too little area to count); since the cells prune, keeping the pairs
  /// costs few node pairs (docs/probability-model.md, section 7, with the command).
  bool pruneImprobable = false;
  /// ADB mode: keep accepted node pairs (p > pMin) as witnesses. Contact generation turns
  /// them off so that the witness slots hold intersecting triangle pairs only.
  bool nodeWitnesses = true;
  /// Contact sampling (with stopAtFirstHit off): once a contact region holds this many
  /// intersecting triangle pairs, the rest of the region is skipped; 0 tests every pair. A
  /// region is a node pair whose depths in A and B add up to at least regionDepth, with
  /// everything below it. Deeply interpenetrating meshes intersect in thousands of triangle
  /// pairs, of which a contact manifold keeps 4: a few per region keep the contacts spread
  /// over the whole overlap at a fraction of the cost. `collides` stays exact: a skipped
  /// region already holds a hit.
  std::uint32_t hitsPerRegion = 0;
  int regionDepth = 8;
  /// Exact mode's descent order (ADB mode follows its probabilities).
  ExactDescent descent = ExactDescent::Auto;
  /// ADB mode's queue key: the table by default. At p_min 0.99, k_min 10 it answered 1.4x to
  /// 1.7x faster than Eq3 with the same errors on the study's models (docs/study.md).
  AdbKey adbKey = AdbKey::Table;
  /// Contact margin, in the trees' (world) units, >= 0: triangle pairs closer than this count
  /// as hits too (Witness::distance > 0), so that a contact can be made before the meshes
  /// touch, as Bullet's convex algorithms do within their breaking threshold. `collides`
  /// then says whether the meshes come within the margin. Boxes are tested grown by the
  /// margin; the probability model ignores it (its cells count intersections only). A full
  /// witness list then keeps the closest pairs (crossing ones count as 0 apart): a closer
  /// hit replaces the farthest witness.
  double contactMargin = 0.0;
  /// Exact mode, a Traversal reset step after step for the same two trees (a physics pair):
  /// keep the node pairs the last query evaluated, each with how far its boxes were apart or
  /// how deeply they overlapped, and walk them again instead of descending from the roots
  /// (traversal_front.h). Only pairs whose margin the bodies' motion since has used up are
  /// tested again, so a resting pair pays for the pairs that changed; what the query visits
  /// and finds is what a descent from the roots would, in the same order (the same
  /// witnesses), and QueryResult::fromScratchNodePairs says what that descent would have
  /// cost. Memory: 32 bytes per evaluated node pair, at most 2 MiB per Traversal. Ignored
  /// by collide() (a new scratch each time gains nothing) and in ADB mode.
  bool keepFront = false;
};

/// Evidence for "collision" handed to contact generation: a pair of nodes accepted on
/// probability, or a pair of triangles that really intersect.
struct Witness {
  std::uint32_t nodeA = 0, nodeB = 0;       // node indices in tree A and tree B
  std::uint32_t triangleA = kNoTriangle;    // tree-order triangle indices when exact
  std::uint32_t triangleB = kNoTriangle;
  float probability = 0.0f;                 // 1 for exact triangle pairs
  /// Exact triangle pairs: 0 when they intersect; within QuerySettings::contactMargin, how
  /// far apart they are.
  float distance = 0.0f;
  static constexpr std::uint32_t kNoTriangle = 0xFFFFFFFFu;
  bool isExact() const { return triangleA != kNoTriangle; }
};

struct QueryResult {
  /// Certain after an exact hit or a traversal that left nothing (nothing pruned either).
  /// Otherwise the more probable answer under the fitted estimate (collision_estimate.h),
  /// however the query stopped: a budget, k_min, or a queue emptied by pruning (where the
  /// estimate is the probability that the paper's answer is right). Exact mode cut before any
  /// hit answers "no" (the baseline of a traversal without a model).
  bool collides = false;
  /// Estimated probability that `collides` is right, in [0, 1]: 1 when certain (an exact hit,
  /// or a query that left nothing open), else max(P, 1 - P) (exact mode cut: 1 - P, below 0.5
  /// where P > 0.5). What it promises: among answers given with confidence c, about a share c
  /// is right, at every budget, for pairs of models it was never fitted on (the expected
  /// calibration error measured per model pair and budget opens docs/probability-model.md,
  /// with the command that checks it on your meshes). A budget stop never claims 0.99 or
  /// more: only a finished query is that sure. Where a budget stops a query after a handful
  /// of node pairs, it says little more than the base rate of such overlaps.
  double confidence = 0.0;
  StopReason stop = StopReason::Completed;
  std::uint64_t nodePairs = 0;       ///< node pairs evaluated (box test, probability)
  /// Node pairs a query from the roots would have evaluated for the same answer: nodePairs
  /// unless QuerySettings::keepFront let the query re-use its last front. Where a budget cut
  /// the query, what was evaluated so far plus what the last front held beyond it.
  std::uint64_t fromScratchNodePairs = 0;
  std::uint64_t triangleTests = 0;   ///< triangle-triangle tests run
  std::uint32_t collisionPairs = 0;  ///< pairs with p > pMin (the paper's k)
  std::uint32_t witnessCount = 0;    ///< witnesses in QueryScratch::witnesses(); 0 for "no"
  std::uint32_t witnessesDropped = 0;
  double seconds = 0.0;              ///< wall clock of the query
};

/// A node pair still queued when an ADB query stopped: unresolved, with its estimates.
struct OpenPair {
  /// The traversal's priority key: Eq. 3's lower bound, or for a pair the cell model is blind
  /// to (a leaf pair, nodes of few triangles or slivers) at least its fill discounted by what
  /// resolving it costs. An order, not a probability: openPairProbability() is one.
  float p;
  float upper;             ///< Pr[X >= 1]: the pair's share of the "no collision" doubt
  std::uint32_t a, b;      ///< node indices in tree A and tree B
  std::uint32_t region;    ///< contact region (QuerySettings::hitsPerRegion) or kNoRegion
  std::uint16_t depthA, depthB;
  float expected;          ///< E[X]: the collision cells the model expects the pair to hold
  /// How full of triangles both nodes are where their boxes meet (the share of occupied cells
  /// on each side, multiplied), [0, 1]; worked out by openPairs().
  float fill = -1.0f;
  static constexpr std::uint32_t kNoRegion = 0xFFFFFFFFu;
};

/// Node pairs one expansion evaluates at most (both nodes' two children): a step's unit of
/// progress.
inline constexpr std::uint64_t kNodePairsPerExpansion = 4;

/// What one Traversal::step may spend. The first step always tests the roots (and expands
/// pairs only within its budget). Every later step with work left and a non-zero budget takes
/// at least one pair off the frontier (up to kNodePairsPerExpansion node pairs, or one leaf
/// pair's triangle tests) whatever its budget, so a caller looping until done() ends. A NaN
/// time budget counts as zero.
struct StepBudget {
  std::uint64_t nodePairs = std::numeric_limits<std::uint64_t>::max();
  double micros = std::numeric_limits<double>::infinity();
};

/// The work of the last Traversal::step (the result's counters are the whole query's).
struct StepWork {
  std::uint64_t nodePairs = 0;
  std::uint64_t triangleTests = 0;
  /// Pairs taken off the frontier: progress even where it cost no node pair or triangle test
  /// (a leaf pair whose triangles' boxes are all apart, a pair of a full contact region).
  std::uint64_t pairsPopped = 0;
  double seconds = 0.0;
};

/// One query between two posed trees, run in steps: built (or reset) from two trees, two
/// poses and the settings, then step(budget) as often as wanted. Between steps the frontier
/// is kept and can be inspected (openPairs()), so each step continues where the last one
/// stopped. The trees must outlive the traversal's use of them (it keeps references, not
/// copies). reset() reuses the memory of earlier queries: steady-state queries do not
/// allocate. Not thread-safe itself; use one per thread (trees may be shared).
class Traversal {
 public:
  Traversal();
  /// reset() at once.
  Traversal(const AdbTree& a, const Pose& poseA, const AdbTree& b, const Pose& poseB,
            const QuerySettings& settings);
  ~Traversal();
  /// A moved-from Traversal may only be destroyed or assigned to.
  Traversal(Traversal&&) noexcept;
  Traversal& operator=(Traversal&&) noexcept;

  /// Starts a new query. Throws SettingsError for invalid settings and PoseError for a bad
  /// pose (see collide()); the budgets of `settings` are not used here (step() takes them).
  void reset(const AdbTree& a, const Pose& poseA, const AdbTree& b, const Pose& poseB,
             const QuerySettings& settings);
  /// Runs until the query is decided or completes, or this step's budget is spent, and
  /// returns the result so far. Calling it after done() returns the same result.
  const QueryResult& step(const StepBudget& budget = {});

  /// Whether the query is decided or complete: further steps do nothing.
  bool done() const;
  /// The answer so far; counters and seconds cover every step since reset().
  const QueryResult& result() const;
  const StepWork& lastStep() const;
  /// The node pairs left unresolved, with the model's estimates: empty when the traversal
  /// completed or exact mode hit; ADB mode keeps its queue when k_min or a hit ends it. ADB
  /// mode: its queue (heap order, not sorted). Exact mode: the depth-first stack, estimated
  /// when a step stopped. Pairs of a contact region whose hits were found are not in it.
  /// Where a budget cut a query, these are the plausible contacts.
  const std::vector<OpenPair>& openPairs() const;
  /// Node pairs accepted on probability and intersecting triangle pairs found so far; empty
  /// while the answer is "no collision" (kept: a later step may still say "collision").
  const std::vector<Witness>& witnesses() const;
  /// What the query has seen so far, the input of its collision estimate
  /// (collision_estimate.h); summarised from the open pairs when called.
  Evidence evidence() const;
  /// Bytes currently reserved (grows to the largest query seen, never shrinks).
  std::size_t capacityBytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

/// Reusable working memory of collide(): one per thread.
class QueryScratch {
 public:
  /// The witnesses of the last query that used this scratch.
  const std::vector<Witness>& witnesses() const { return m_traversal.witnesses(); }
  /// The node pairs the last query left unresolved (Traversal::openPairs()).
  const std::vector<OpenPair>& openPairs() const { return m_traversal.openPairs(); }
  /// Bytes currently reserved (grows to the largest query seen, never shrinks).
  std::size_t capacityBytes() const { return m_traversal.capacityBytes(); }

 private:
  friend QueryResult collide(const AdbTree&, const Pose&, const AdbTree&, const Pose&,
                             const QuerySettings&, QueryScratch&);
  Traversal m_traversal;
};

/// What makes a pose unusable, if anything: the checks collide() and Traversal::reset()
/// make (and throw PoseError for), without throwing. A physics engine checks its bodies
/// with it once per step.
enum class PoseDefect {
  None,
  NonFinite,       ///< a NaN or infinite entry
  TooFar,          ///< a translation beyond 1e150 (the largest coordinate meshes may hold)
  NotOrthonormal,  ///< |R^T R - I| > 1e-6: scaled, sheared or drifted; rotations are
                   ///< inverted by transposing
};
PoseDefect poseDefect(const Pose& pose);
/// One line saying what is wrong ("has a non-finite entry", ...); empty for None.
const char* describe(PoseDefect defect);

/// Tests tree `a` at `poseA` against tree `b` at `poseB` (poses map each mesh's own
/// coordinates to the world). Throws SettingsError for invalid settings (pMin outside [0, 1],
/// kMin < 1, NaN or negative budget, negative regionDepth) and PoseError for a bad pose
/// (non-finite, a translation beyond 1e150, or a rotation off orthonormal by more than 1e-6;
/// a negative or non-finite contactMargin);
/// never throws for a valid call.
QueryResult collide(const AdbTree& a, const Pose& poseA, const AdbTree& b, const Pose& poseB,
                    const QuerySettings& settings, QueryScratch& scratch);

/// Throws SettingsError naming the first invalid field of `settings`.
void validate(const QuerySettings& settings);

}  // namespace adb
