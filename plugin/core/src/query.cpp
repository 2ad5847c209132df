// The collision query: the paper's probability-guided traversal (Fig. 3) and the exact mode,
// run in steps by adb::Traversal.
//
//   traverse(A, B):                                  # ADB mode, paper Fig. 3 plus budgets
//     q = max-queue by priority; k = 0; q.insert(rootA, rootB, 1)
//     while q not empty and budget left:
//       (A, B) = q.pop()
//       if A and B are leaves: test their triangles exactly; a hit is certain -> collision
//       for all children A[i], B[j] (a leaf is its own only child):
//         p = computeProb(A[i], B[j])                # pair_kernel.h, pair_probability.cpp
//         if p > p_min and not both leaves: k += 1, keep as witness
//                                          if k >= k_min: return collision
//         if p > 0: q.insert(A[i], B[j], priority)
//
// The priority (QuerySettings::adbKey) is by default a table that approximates Eq. 3 from E[X]
// and the depth term, in a bucket queue (priority_table.h, bucket_queue.h); Eq. 3 itself is
// then evaluated only where its pre-test says p could exceed p_min, so the same pairs are
// accepted. AdbKey::Eq3 keeps the paper's order: Eq. 3 for every pair, in a binary heap.
//     return the better-supported answer (see confidence below)
//
// Leaf pairs are never accepted on probability: the tree keeps triangles, so they are decided
// exactly when popped. An exact hit, or a traversal that ran out of pairs without pruning any,
// is certain. Every other stop answers with the fitted estimate (collision_estimate.h):
// P(collision) from the open pairs (a partition of what is left, so none is nested in
// another) and what was accepted and pruned; the answer is the more probable side and the
// confidence its probability. At k_min, or a queue emptied by pruning, the estimate is the
// probability that the paper's answer is right (fitted apart: the evidence differs there).
//
// Exact mode is a depth-first descent over overlapping boxes. Cut by a budget, its stack is
// estimated by the same model (openPairs()), it answers "no" unless it has found a hit, with
// the estimate's 1 - P as its confidence; the next step continues from it. Contact generation
// samples hits per contact region (hitsPerRegion): once a region holds its quota, its remaining
// pairs are skipped at no cost, in either mode.
//
// Each expansion tests the up to four child pairs together (pair_kernel.h): a child meets two
// children of the other node, so each box is posed in the other frame once, and the tests of
// one child against both children of the other run in one register.
#include "adb/core/query.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "adb/core/triangle_distance.h"
#include "adb/core/triangle_test.h"
#include "bucket_queue.h"
#include "format_number.h"
#include "pair_probability.h"
#include "priority_table.h"
#include "probability_tables.h"
#include "traversal_front.h"

namespace adb {
namespace {

// The tables behind the ADB key and the probabilities, built when the library loads rather
// than on first use, inside the first query's clock: a process's first query under a 50 us
// budget evaluated 1 node pair in 0.5 to 2.6 ms and answered from the roots
// (ColdStart.TheFirstBudgetedQueryOfAProcessDoesAsMuchAsTheSecond).
[[maybe_unused]] const bool kQueryTablesReady = [] {
  detail::priorityTable();
  detail::prepareProbabilityTables();
  return true;
}();

using Clock = std::chrono::steady_clock;
using Entry = OpenPair;
constexpr std::uint32_t kNoRegion = OpenPair::kNoRegion;
constexpr std::uint64_t kUnlimited = std::numeric_limits<std::uint64_t>::max();
// Trees deeper than this (a depth must fit QueueEntry's byte) are ordered by Eq. 3.
constexpr int kMaxQueueDepth = 255;
// Witness slots and ADB heap entries reserved when a scratch first meets its trees (more
// grow on demand).
constexpr std::size_t kReservedWitnesses = 128;
constexpr std::size_t kReservedOpenPairs = 256;
// Exact mode's stack entries carry no estimate until a budget stop asks for one.
constexpr float kUnestimated = -1.0f;
// A pair the cell model is blind to (Traversal::Impl::blind) is keyed by how full of triangles
// both nodes are where their boxes meet, scaled by what resolving it costs: 1 up to this many
// triangles in the two nodes together (a leaf pair: at most 16 triangle tests), falling as
// 1 / triangles beyond. Two nodes of a few large triangles are then resolved exactly early,
// for a handful of triangle tests, instead of queued last for their E[X] of about 0 (issue 43:
// a budget stopped with them open, and the estimate read them as "no").
constexpr double kCheapBlindTriangles = 8.0;

// The clock is read once this much work has been done since the last read, counting 4 per
// popped pair (its evaluations, ~0.1 us each) and 1 per triangle test: at most every 64 units
// (~2-3 us), so that a short query is not dominated by clock reads, and for budgets under 4 us
// about every 16 units per microsecond of budget, at least every pair (4 units): a fixed 64 made
// budgets of 1 and 2 us run alike. A budget overshoots by one interval at most (plus one leaf
// pair: at most 15 x 15 triangle tests, which are never interrupted).
constexpr unsigned kMaxClockInterval = 64;
constexpr unsigned kMinClockInterval = 4;
constexpr double kClockUnitsPerMicro = 16.0;

unsigned clockInterval(double budgetMicros) {
  const double units = std::clamp(budgetMicros * kClockUnitsPerMicro,
                                  static_cast<double>(kMinClockInterval),
                                  static_cast<double>(kMaxClockInterval));
  return static_cast<unsigned>(units);
}

bool heapLess(const Entry& x, const Entry& y) { return x.p < y.p; }

// The doubt an unresolved pair carries: Pr[X >= 1], or where rounding left one side no
// possible collision cell (so Pr[X >= 1] = 0 for boxes that do overlap), E[X] before
// rounding, as for a pruned pair (Markov).
double doubtOf(const detail::PairEstimate& est) {
  return est.upper > 0.0 ? est.upper : std::min(1.0, est.expected);
}

// Whether boxes [loX, hiX] and [loY, hiY] are separated along some axis by more than `gap`.
bool boxesApart(const Vec3& loX, const Vec3& hiX, const Vec3& loY, const Vec3& hiY, double gap) {
  return (loX.array() > hiY.array() + gap).any() || (loY.array() > hiX.array() + gap).any();
}

void validatePose(const Pose& p, const char* which) {
  const PoseDefect defect = poseDefect(p);
  if (defect == PoseDefect::None) return;
  std::string why = describe(defect);
  if (defect == PoseDefect::TooFar) {
    why = "has a translation of " + detail::formatNumber(p.translation.cwiseAbs().maxCoeff()) +
          "; poses are supported up to " + detail::formatNumber(detail::kMaxCoordinate) +
          " from the origin";
  } else if (defect == PoseDefect::NotOrthonormal) {
    why += " (|R^T R - I| = " +
           detail::formatNumber(
               (p.rotation.transpose() * p.rotation - Mat3::Identity()).cwiseAbs().maxCoeff()) +
           ")";
  }
  throw PoseError(std::string("collide: pose ") + which + " " + why);
}

// The children of a node for the simultaneous descent: a leaf is its own only child.
int children(const Node& n, std::uint32_t self, std::uint32_t out[2]) {
  if (n.isLeaf()) {
    out[0] = self;
    return 1;
  }
  out[0] = n.firstChild();
  out[1] = n.firstChild() + 1;
  return 2;
}

}  // namespace

// The traversal inverts rotations by transposing them: a scaled or sheared "rotation" would
// silently misplace every box, so it is refused at the door.
PoseDefect poseDefect(const Pose& p) {
  constexpr double kOrthonormalTolerance = 1e-6;
  if (!p.rotation.allFinite() || !p.translation.allFinite()) return PoseDefect::NonFinite;
  if (p.translation.cwiseAbs().maxCoeff() > detail::kMaxCoordinate) return PoseDefect::TooFar;
  const double off = (p.rotation.transpose() * p.rotation - Mat3::Identity()).cwiseAbs().maxCoeff();
  return off > kOrthonormalTolerance ? PoseDefect::NotOrthonormal : PoseDefect::None;
}

const char* describe(PoseDefect defect) {
  switch (defect) {
    case PoseDefect::None: return "";
    case PoseDefect::NonFinite: return "has a non-finite entry";
    case PoseDefect::TooFar:
      return "has a translation beyond 1e+150 from the origin, the largest supported";
    case PoseDefect::NotOrthonormal: return "has a rotation that is not orthonormal";
  }
  return "";
}

struct Traversal::Impl {
  // --- the query, fixed by reset() -------------------------------------------------------
  detail::TreeConstants a{nullptr, 0}, b{nullptr, 0};
  detail::RelativeFrame frame;
  // The contact margin in force: QuerySettings::contactMargin, shrunk to the farthest kept
  // witness once the witness list is full (shrinkMargin), and the box tests' slack without it.
  double margin = 0.0;
  double slackWithoutMargin = 0.0;
  QuerySettings settings;
  bool budgeted = false;  // a budget may cut the query (ExactDescent::Auto: deepest first)
  bool deepestFirst = false;  // exact mode descends the deepest overlap first

  // --- state kept between steps ------------------------------------------------------------
  std::vector<Entry> heap;  // ADB: max-heap by p; exact: the open pairs of a cut (openPairs())
  // Exact mode's depth-first stack, 16 bytes an entry. A cut copies it into `heap` with the
  // model's estimates; entries below `stackLowWater` (the lowest the stack has been since)
  // were not popped, so their copies and estimates are kept: a query resumed step after step
  // estimates only what it pushed since its last stop.
  struct StackEntry {
    std::uint32_t a, b, region;
    std::uint16_t depthA, depthB;
  };
  static_assert(sizeof(StackEntry) == 16, "a stack entry is 16 bytes");
  std::vector<StackEntry> stack;
  std::size_t stackLowWater = 0;
  // ADB mode with the table key (AdbKey::Table): the bucket queue, and running sums over it
  // for the evidence of a stop. `heap` then mirrors it only when openPairs() asks.
  struct QueueEntry {
    std::uint32_t a, b, region;
    std::uint8_t depthA, depthB;  // deeper trees (kMaxQueueDepth) are ordered by Eq. 3
    std::uint16_t expected;       // E[X] as a float's 16 bits after the sign (encodeExpected)
  };
  static_assert(sizeof(QueueEntry) == 16, "a queue entry is 16 bytes");
  bool tableKey = false;
  detail::BucketQueue<QueueEntry, detail::kPriorityBuckets> queue;
  double openExpected = 0.0;  // sum of E[X] over the queue
  double openDoubt = 0.0;     // sum of min(1, E[X]) over the queue
  std::uint32_t blindOpen = 0;  // queued pairs the model is blind to
  double blindLogMiss = 0.0;    // sum of log(1 - key) over them
  bool openStale = false;     // `heap` does not mirror the queue
  // What an expansion at depth sum d needs besides its pairs, worked out on first use in a
  // query (a division and up to ten multiplications, shared by every expansion at d).
  struct DepthTerms {
    double lb = 0.0;   // Eq. 3's depth term
    int column = 0;    // its column of the priority table
    int passing = -1;  // smallestPassingCells(lb, pMin); -1: not worked out yet
  };
  std::vector<DepthTerms> depthTerms;
  const detail::PriorityTable* priorities = &detail::priorityTable();
  std::vector<Witness> witnesses;
  std::vector<std::uint32_t> regionHits;  // hits found per contact region
  QueryResult result;
  bool started = false;  // the roots have been tested
  bool finished = true;  // nothing to run until reset()
  double prunedMass = 0.0;    // sum of min(1, E[X]) over the pairs pruned for p = 0
  double prunedExpected = 0.0;  // sum of E[X] over them
  bool exactHit = false;
  bool witnessesFull = false;  // stopWhenWitnessesFull: the last hit filled the witnesses
  mutable double rootFill = -1.0;  // the roots' occupied fill, worked out when evidence needs it
  bool inStep = false;             // work.nodePairs is not yet in result.nodePairs

  // --- the front (QuerySettings::keepFront), kept across reset() -----------------------------
  // `front` is the last walk's record (traversal_front.h), `nextFront` the one being written.
  std::vector<detail::FrontEntry> front, nextFront;
  detail::FrontReference reference;
  const AdbTree* frontTreeA = nullptr;
  const AdbTree* frontTreeB = nullptr;
  double frontMargin = 0.0;
  double radiusA = 0.0, radiusB = 0.0;
  double motion = 0.0;      // this query's bound on how far the trees moved since `reference`
  // Moving the reference pose uses up that much of every certificate. Instead of rewriting
  // each, it is summed here: an entry holds |certificate| - consumed (a new one is stored
  // with consumed added), and only when the sum grows past the trees' size are the entries
  // rewritten. `reach` = motion + consumed: what a certificate must exceed to hold.
  double consumed = 0.0;
  double reach = 0.0;
  bool walking = false;     // this query walks a front instead of descending from the roots
  bool walkOpen = false;    // a walk began and its record is not yet in `front`
  bool recording = true;    // nextFront is under kMaxFrontEntries
  std::uint64_t fromScratch = 0;  // node pairs a descent from the roots evaluates
  static constexpr std::size_t kNotRecorded = ~std::size_t{0};
  struct WalkFrame {
    std::size_t parentAt = kNotRecorded;  // the parent's entry in nextFront
    std::uint32_t region = kNoRegion;  // the parent's contact region
    bool fromOld = false;           // children read from `front`, else `kids`
    std::size_t oldCursor = 0;      // fromOld: the next child in `front`
    std::size_t oldEnd = 0;         // fromOld: one past the parent's last entry in `front`
    std::uint8_t kidCount = 0, kidNext = 0;
    detail::FrontEntry kids[4];     // a fresh expansion's children, in processing order
    bool kidOverlaps[4] = {false, false, false, false};
    // The child taken and waiting for its leaf test or its expansion, with what lay below it
    // in `front` ([pendingBegin, pendingEnd), empty for a fresh one).
    bool hasPending = false;
    detail::FrontEntry pending{};
    std::size_t pendingAt = kNotRecorded;  // its entry in nextFront
    std::uint32_t pendingRegion = kNoRegion;
    std::size_t pendingBegin = 0, pendingEnd = 0;
  };
  std::vector<WalkFrame> frames;

  // --- the current step ----------------------------------------------------------------------
  StepWork work;
  StepBudget budget;
  Clock::time_point stepStart;
  bool timed = false;
  unsigned interval = kMaxClockInterval;  // work units between clock reads this step
  unsigned workSinceClock = 0;
  bool firstCheck = true;   // the first check reads the clock: a zero budget stops at once
  bool progressed = false;  // this step has expanded a pair (every step makes progress)

  // Buffers sized by the trees before a query's clock starts, so that the first query of a
  // scratch does not pay for growing them (issue 37): exact mode's stack (and a cut's open
  // pairs) gain at most 3 pairs per level of the two trees (an expansion pops one and pushes
  // up to 4), the witnesses at most maxWitnesses (kept to a page's worth: most queries find
  // few), and ADB's queue about a pair per hundred nodes in each bucket (ADB mode's open
  // pairs grow with the front, which no bound short of n m holds: beyond this they grow).
  void reserveFor(const AdbTree& ta, const AdbTree& tb) {
    const std::size_t nodes = ta.nodes().size() + tb.nodes().size();
    if (nodes <= reservedNodes && (settings.mode != QueryMode::Adb || queueReserved)) return;
    reservedNodes = std::max(reservedNodes, nodes);
    const std::size_t levels = static_cast<std::size_t>(ta.maxDepth() + tb.maxDepth()) + 1;
    stack.reserve(3 * levels + 1);
    heap.reserve(std::max<std::size_t>(3 * levels + 1, kReservedOpenPairs));
    witnesses.reserve(std::min<std::size_t>(settings.maxWitnesses, kReservedWitnesses));
    if (settings.mode == QueryMode::Adb) {
      queue.reserve(std::clamp<std::size_t>(nodes / 256, 8, 64));
      queueReserved = true;
    }
  }
  std::size_t reservedNodes = 0;  // the largest pair of trees reserveFor() sized for
  bool queueReserved = false;

  void reset(const AdbTree& ta, const Pose& poseA, const AdbTree& tb, const Pose& poseB,
             const QuerySettings& s) {
    validate(s);
    validatePose(poseA, "A");
    validatePose(poseB, "B");
    if (walkOpen) closeWalk();  // a walk a budget left unfinished: keep what it recorded
    a = {&ta, ta.maxDepth()};
    b = {&tb, tb.maxDepth()};
    frame = detail::RelativeFrame::between(ta, poseA, tb, poseB);
    // Every box test separates along unit axes: a gap larger than the margin along any of
    // them proves the nodes farther apart than the margin.
    slackWithoutMargin = frame.slack;
    margin = s.contactMargin;
    frame.slack += s.contactMargin;
    settings = s;
    reserveFor(ta, tb);
    heap.clear();
    stack.clear();
    stackLowWater = 0;
    queue.clear();
    openExpected = openDoubt = 0.0;
    blindOpen = 0;
    blindLogMiss = 0.0;
    rootFill = -1.0;
    openStale = false;
    tableKey = s.mode == QueryMode::Adb && s.adbKey == AdbKey::Table &&
               ta.maxDepth() <= kMaxQueueDepth && tb.maxDepth() <= kMaxQueueDepth;
    if (tableKey) {
      const std::size_t sums = static_cast<std::size_t>(ta.maxDepth() + tb.maxDepth()) + 1;
      depthTerms.assign(sums, DepthTerms{});
    }
    witnesses.clear();
    regionHits.clear();
    result = QueryResult{};
    started = finished = exactHit = witnessesFull = false;
    prunedMass = prunedExpected = 0.0;
    budgeted = deepestFirst = false;
    work = StepWork{};
    // (A front records the trees' or the deepest-first order; most cells first descends from
    // the roots.)
    walking = s.keepFront && s.mode == QueryMode::Exact &&
              s.descent != ExactDescent::MostCellsFirst &&
              ta.maxDepth() <= detail::kMaxFrontDepth && tb.maxDepth() <= detail::kMaxFrontDepth;
    if (walking) startFront(ta, tb);
  }

  // Keeps the front where it is the same two trees and margin, and measures how far they
  // moved since its reference pose; past kRebaseFraction of their size the certificates are
  // moved to the current pose (resting contact jitters far less: a fixed reference lets its
  // certificates last, instead of losing each step's jitter).
  void startFront(const AdbTree& ta, const AdbTree& tb) {
    constexpr double kRebaseFraction = 1e-3;
    if (frontTreeA != &ta || frontTreeB != &tb || frontMargin != settings.contactMargin) {
      front.clear();
      consumed = 0.0;
      frontTreeA = &ta;
      frontTreeB = &tb;
      frontMargin = settings.contactMargin;
      radiusA = detail::treeRadius(ta);
      radiusB = detail::treeRadius(tb);
      reference = detail::FrontReference::of(frame);
    }
    motion = reference.motion(frame, radiusA, radiusB);
    if (!(motion <= kRebaseFraction * (radiusA + radiusB))) {
      consumed += motion;
      if (!std::isfinite(consumed)) {
        front.clear();
        consumed = 0.0;
      } else if (consumed > radiusA + radiusB) {  // float certificates would lose precision
        detail::settleConsumed(front, consumed);
        consumed = 0.0;
      }
      reference = detail::FrontReference::of(frame);
      motion = frame.slack;
    }
    reach = motion + consumed;
  }

  const QueryResult& step(const StepBudget& stepBudget) {
    work = StepWork{};
    if (finished) return result;
    budget = stepBudget;
    if (std::isnan(budget.micros)) budget.micros = 0.0;  // no time is the safe reading
    budgeted = budgeted || budget.nodePairs != kUnlimited || std::isfinite(budget.micros);
    deepestFirst = settings.descent == ExactDescent::DeepestFirst ||
                   (settings.descent == ExactDescent::Auto && budgeted);
    stepStart = Clock::now();
    timed = std::isfinite(budget.micros);
    interval = timed ? clockInterval(budget.micros) : kMaxClockInterval;
    workSinceClock = 0;
    firstCheck = true;
    progressed = false;
    inStep = true;
    if (walking) {
      runFront();
    } else if (settings.mode == QueryMode::Exact) {
      runExact();
    } else if (tableKey) {
      runAdbTable();
    } else {
      runAdb();
    }
    inStep = false;
    work.seconds = std::chrono::duration<double>(Clock::now() - stepStart).count();
    result.nodePairs += work.nodePairs;
    result.triangleTests += work.triangleTests;
    result.seconds += work.seconds;
    if (!walking) result.fromScratchNodePairs = result.nodePairs;
    // A "no" shows no witnesses, but keeps them: a later step may still say "collision".
    result.witnessCount = result.collides ? static_cast<std::uint32_t>(witnesses.size()) : 0;
    finished = !isBudgetStop(result.stop);
    return result;
  }

  // --- budgets -------------------------------------------------------------------------
  // Checked before a pair is expanded (up to 4 evaluations), so a pair is never half-expanded.
  // The first expansion of a step is free unless the budget is zero: every step with a
  // non-zero budget makes progress, so a caller looping until done() cannot livelock; a
  // first step's roots test is its progress (nodePairs <= max(1, budget) for collide()).
  // `cost`: the node pairs the next piece of work evaluates at most.
  bool budgetLeft(std::uint64_t cost = kNodePairsPerExpansion) {
    const bool free =
        !progressed && budget.nodePairs > 0 && budget.micros > 0.0 && work.nodePairs == 0;
    if (free) {
      progressed = true;
      return true;
    }
    if (work.nodePairs + cost > budget.nodePairs) {
      result.stop = StopReason::WorkBudget;
      return false;
    }
    if (!timed) return true;
    workSinceClock += 4;
    if (workSinceClock >= interval || firstCheck) {
      workSinceClock = 0;
      firstCheck = false;
      const double us = std::chrono::duration<double, std::micro>(Clock::now() - stepStart).count();
      if (us >= budget.micros) {
        result.stop = StopReason::TimeBudget;
        return false;
      }
    }
    return true;
  }

  // --- witnesses -----------------------------------------------------------------------
  void addWitness(const Witness& w) {
    if (witnesses.size() < settings.maxWitnesses) {
      witnesses.push_back(w);
      return;
    }
    ++result.witnessesDropped;
    // With a contact margin a full list keeps the closest pairs: the contacts that matter
    // are where the meshes meet first, not the first pairs the descent happened to find.
    if (!(settings.contactMargin > 0.0) || witnesses.empty()) return;
    // One pass: the farthest witness, and the farthest of the others (the list's farthest
    // once that one is replaced).
    std::size_t farthest = 0;
    float others = -std::numeric_limits<float>::infinity();
    for (std::size_t i = 1; i < witnesses.size(); ++i) {
      if (witnesses[i].distance > witnesses[farthest].distance) {
        others = std::max(others, witnesses[farthest].distance);
        farthest = i;
      } else {
        others = std::max(others, witnesses[i].distance);
      }
    }
    if (w.distance < witnesses[farthest].distance) {
      witnesses[farthest] = w;
      shrinkMargin(std::max(others, w.distance));
    } else {
      shrinkMargin(witnesses[farthest].distance);
    }
  }

  // Branch and bound on the closest pairs: once the witness list is full, no pair farther
  // apart than its farthest witness can enter it, so the margin shrinks to that distance and
  // the box tests prune every node pair beyond it. Why: a fast body's speculative contacts
  // (a gear falling flat onto a floor) have hundreds of triangle pairs within the distance
  // the bodies close in a step, and enumerating them all cost a robot arm falling into a
  // room 188,000 node pairs in one step (docs/bullet-results.md, "CCD: fast mesh bodies
  // against thin walls and floors"). Not while walking a front: its certificates were
  // measured with the settings' margin.
  void shrinkMargin(double farthest) {
    if (walking || !(farthest < margin)) return;
    margin = farthest;
    frame.slack = slackWithoutMargin + margin;
  }

  // Whether the hit just found ends the query (stopAtFirstHit, or the witnesses are full),
  // and why.
  bool hitEndsQuery() const { return settings.stopAtFirstHit || witnessesFull; }
  StopReason hitStop() const {
    return witnessesFull ? StopReason::WitnessesFull : StopReason::ExactHit;
  }

  // --- contact regions (QuerySettings::hitsPerRegion) -------------------------------------
  // The region of a child pair at depths (da, db): its parent's, or a new one where the pair
  // is the first on its path to reach regionDepth.
  std::uint32_t childRegion(std::uint32_t parent, int da, int db) {
    if (parent != kNoRegion) return parent;
    if (settings.hitsPerRegion == 0 || da + db < settings.regionDepth) return kNoRegion;
    regionHits.push_back(0);
    return static_cast<std::uint32_t>(regionHits.size() - 1);
  }

  // A region with its hits found: the rest of it is skipped.
  bool regionFull(std::uint32_t region) const {
    return region != kNoRegion && regionHits[region] >= settings.hitsPerRegion;
  }

  // Tests the triangle pairs of two leaves (all, or until their region is full); records
  // hits. Returns true on a hit.
  bool testLeaves(std::uint32_t ia, std::uint32_t ib, std::uint32_t region) {
    const Node& na = a.tree->nodes()[ia];
    const Node& nb = b.tree->nodes()[ib];
    const auto& va = a.tree->localVertices();
    const auto& vb = b.tree->localVertices();
    const auto& ta = a.tree->triangles();
    const auto& tb = b.tree->triangles();
    // B's triangles mapped into A's frame once per leaf pair (at most 15 x 3 points), and
    // the boxes of both leaves' triangles in that frame (Eigen leaves them uninitialised:
    // nothing is written for the slots a leaf does not use).
    Vec3 mapped[15][3];
    Vec3 loA[15], hiA[15], loB[15], hiB[15];
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (std::uint32_t j = 0; j < nb.triangleCount(); ++j) {
      for (int k = 0; k < 3; ++k) {
        mapped[j][k] = frame.bToA(vb[tb[nb.firstTriangle() + j][k]]);
      }
      loB[j] = mapped[j][0].cwiseMin(mapped[j][1]).cwiseMin(mapped[j][2]);
      hiB[j] = mapped[j][0].cwiseMax(mapped[j][1]).cwiseMax(mapped[j][2]);
      lo = lo.cwiseMin(loB[j]);
      hi = hi.cwiseMax(hiB[j]);
    }
    for (std::uint32_t i = 0; i < na.triangleCount(); ++i) {
      const Triangle& t = ta[na.firstTriangle() + i];
      loA[i] = va[t[0]].cwiseMin(va[t[1]]).cwiseMin(va[t[2]]);
      hiA[i] = va[t[0]].cwiseMax(va[t[1]]).cwiseMax(va[t[2]]);
      lo = lo.cwiseMin(loA[i]);
      hi = hi.cwiseMax(hiA[i]);
    }
    // Triangle pairs whose boxes are apart by more than this are skipped untested: it is a
    // thousand times trianglesIntersect's tolerance (1e-12 of the pair's extent) beyond the
    // contact margin, so the answer is the one the tests would give. Most pairs of two
    // overlapping leaves are apart.
    const double gap = 1e-9 * (hi - lo).maxCoeff() + margin;
    bool hit = false;
    for (std::uint32_t i = 0; i < na.triangleCount(); ++i) {
      const Triangle& t = ta[na.firstTriangle() + i];
      for (std::uint32_t j = 0; j < nb.triangleCount(); ++j) {
        if (boxesApart(loA[i], hiA[i], loB[j], hiB[j], gap)) continue;
        ++work.triangleTests;
        ++workSinceClock;
        float distance = 0.0f;
        if (!trianglesIntersect(va[t[0]], va[t[1]], va[t[2]], mapped[j][0], mapped[j][1],
                                mapped[j][2])) {
          if (!(margin > 0.0)) continue;
          const double d = triangleDistance(va[t[0]], va[t[1]], va[t[2]], mapped[j][0],
                                            mapped[j][1], mapped[j][2])
                               .distance;
          if (!(d <= margin)) continue;
          // Rounded up: a near pair never reads as touching.
          distance = std::max(std::nextafter(0.0f, 1.0f), static_cast<float>(d));
        }
        hit = true;
        Witness w;
        w.distance = distance;
        w.nodeA = ia;
        w.nodeB = ib;
        w.triangleA = na.firstTriangle() + i;
        w.triangleB = nb.firstTriangle() + j;
        w.probability = 1.0f;
        addWitness(w);
        if (settings.stopAtFirstHit) return true;
        if (settings.stopWhenWitnessesFull && witnesses.size() >= settings.maxWitnesses) {
          witnessesFull = true;
          return true;
        }
        if (region != kNoRegion && ++regionHits[region] >= settings.hitsPerRegion) {
          return true;
        }
      }
    }
    return hit;
  }

  // The children of the nodes of a popped pair (a leaf is its own only child) and their depths.
  struct Expansion {
    std::uint32_t ca[2], cb[2];
    int countA, countB;
    int depthA, depthB;
  };

  // The expansion of pair (ia, ib) at depths (depthA, depthB): every mode's and key's.
  Expansion expand(std::uint32_t ia, int depthA, std::uint32_t ib, int depthB) const {
    return expand(a.tree->nodes()[ia], ia, depthA, b.tree->nodes()[ib], ib, depthB);
  }
  // The same for nodes the caller has already read (exact mode: 2 % of its instructions).
  static Expansion expand(const Node& na, std::uint32_t ia, int depthA, const Node& nb,
                          std::uint32_t ib, int depthB) {
    Expansion x;
    x.countA = children(na, ia, x.ca);
    x.countB = children(nb, ib, x.cb);
    x.depthA = na.isLeaf() ? depthA : depthA + 1;
    x.depthB = nb.isLeaf() ? depthB : depthB + 1;
    return x;
  }

  // Up to four items in ascending key order (ties keep their arrival order): the few child
  // pairs of one expansion.
  template <class Item, class Key>
  static void insertAscending(Item* items, Key* keys, int& n, const Item& item, Key key) {
    int k = n++;
    for (; k > 0 && keys[k - 1] > key; --k) {
      items[k] = items[k - 1];
      keys[k] = keys[k - 1];
    }
    items[k] = item;
    keys[k] = key;
  }

  // A pair dropped for p = 0 (QuerySettings::pruneImprobable): its E[X] stays evidence.
  void notePruned(double expected) {
    prunedMass += std::min(1.0, expected);
    prunedExpected += expected;
  }

  detail::PairKernel pairsOf(const Expansion& x) const {
    return detail::PairKernel(*a.tree, x.ca, x.countA, *b.tree, x.cb, x.countB, frame);
  }

  bool bothLeaves(const Entry& e) const {
    return a.tree->nodes()[e.a].isLeaf() && b.tree->nodes()[e.b].isLeaf();
  }

  // --- exact mode: depth-first over overlapping boxes ----------------------------------
  void runExact() {
    if (!started) {
      started = true;
      ++work.nodePairs;
      if (!detail::nodesOverlap(a, 0, b, 0, frame)) {
        finish(false, 1.0, StopReason::Completed);
        return;
      }
      stack.push_back(StackEntry{0, 0, childRegion(kNoRegion, 0, 0), 0, 0});
    }
    const Node* nodesA = a.tree->nodes().data();
    const Node* nodesB = b.tree->nodes().data();
    while (!stack.empty()) {
      if (regionFull(stack.back().region)) {  // skipping costs no budget
        popStack();
        ++work.pairsPopped;
        continue;
      }
      if (!budgetLeft()) {
        // The stack is what is left unexplored: estimated by the model, it gives the cut
        // query its confidence and the caller its plausible contacts (openPairs()).
        openStack();
        finish(exactHit, exactHit ? 1.0 : 1.0 - collisionProbability(evidence()), result.stop);
        return;
      }
      const StackEntry e = stack.back();
      popStack();
      ++work.pairsPopped;
      const Node& na = nodesA[e.a];
      const Node& nb = nodesB[e.b];
      if (na.isLeaf() && nb.isLeaf()) {
        if (testLeaves(e.a, e.b, e.region)) {
          exactHit = true;
          if (hitEndsQuery()) {
            stack.clear();  // decided: nothing is left open
            heap.clear();
            finish(true, 1.0, hitStop());
            return;
          }
        }
        continue;
      }
      pushOverlappingChildren(e, expand(na, e.a, e.depthA, nb, e.b, e.depthB));
    }
    heap.clear();
    finish(exactHit, 1.0, StopReason::Completed);
  }

  void popStack() {
    stack.pop_back();
    stackLowWater = std::min(stackLowWater, stack.size());
  }

  // Exact mode's expansion: the overlapping children go on the stack, the first to pop last.
  // In the trees' order they are pushed as the kernel reports them; deepest first, sorted.
  void pushOverlappingChildren(const StackEntry& e, const Expansion& x) {
    if (settings.descent == ExactDescent::MostCellsFirst) {
      pushMostCellsLast(e, x);
      return;
    }
    if (deepestFirst) {
      ChildTest kids[4];
      for (int k = orderedChildren(x, false, kids); k-- > 0;) {
        if (kids[k].overlaps) pushChild(kids[k].a, kids[k].b, e.region, x);
      }
      return;
    }
    detail::PairKernel pairs = pairsOf(x);
    const unsigned mask = pairs.overlapMask();
    work.nodePairs += static_cast<std::uint64_t>(x.countA * x.countB);
    if (mask == 0) return;
    for (int i = 0; i < x.countA; ++i) {
      for (int j = 0; j < x.countB; ++j) {
        if ((mask >> detail::PairKernel::index(i, j)) & 1u) {
          pushChild(x.ca[i], x.cb[j], e.region, x);
        }
      }
    }
  }

  // MostCellsFirst: the overlapping children pushed by ascending E[X] (the most pops first);
  // ties keep the trees' order.
  void pushMostCellsLast(const StackEntry& e, const Expansion& x) {
    detail::PairKernel pairs = pairsOf(x);
    const unsigned mask = pairs.overlapMask();
    work.nodePairs += static_cast<std::uint64_t>(x.countA * x.countB);
    if (mask == 0) return;
    detail::CellCounts counts[4];
    pairs.cellCounts(mask, counts);
    int order[4];
    double key[4];
    int n = 0;
    for (int i = 0; i < x.countA; ++i) {
      for (int j = 0; j < x.countB; ++j) {
        const int p = detail::PairKernel::index(i, j);
        if ((mask >> p) & 1u) insertAscending(order, key, n, p, counts[p].expected);
      }
    }
    for (int k = 0; k < n; ++k) {
      pushChild(x.ca[order[k] / 2], x.cb[order[k] % 2], e.region, x);
    }
  }

  void pushChild(std::uint32_t ia, std::uint32_t ib, std::uint32_t parentRegion,
                 const Expansion& x) {
    stack.push_back(StackEntry{ia, ib, childRegion(parentRegion, x.depthA, x.depthB),
                               static_cast<std::uint16_t>(x.depthA),
                               static_cast<std::uint16_t>(x.depthB)});
  }

  // A cut exact query's stack as its open pairs (`heap`), in stack order, with the model's
  // estimates: pairs of full regions are resolved, not open, and are dropped from both.
  void openStack() {
    if (!regionHits.empty()) {
      const auto full = [this](const StackEntry& e) { return regionFull(e.region); };
      const auto firstFull = std::find_if(stack.begin(), stack.end(), full);
      stackLowWater = std::min(stackLowWater, static_cast<std::size_t>(firstFull - stack.begin()));
      stack.erase(std::remove_if(firstFull, stack.end(), full), stack.end());
    }
    heap.resize(std::min(stackLowWater, heap.size()));
    for (std::size_t k = heap.size(); k < stack.size(); ++k) {
      const StackEntry& e = stack[k];
      heap.push_back(Entry{kUnestimated, 1.0f, e.a, e.b, e.region, e.depthA, e.depthB, 0.0f});
    }
    stackLowWater = stack.size();
    estimateFrontier();
  }

  // The child pairs of an expansion in the order exact mode pops them, each with whether it
  // overlaps and, with `measure`, how far apart or deep (PairKernel::measure, for the
  // fronts). Deepest first (ExactDescent), the deepest box overlap comes first: a budget that
  // cuts the descent has then seen the deepest contacts, the ones that keep bodies apart.
  // Otherwise the trees' order reversed (the stack pops the last child first), which samples
  // the same triangle pairs step after step (deepest first, near-equal depths swap with every
  // small motion, and the contacts of a resting stack jumped: its top boxes drifted up to
  // 40 % further). In the trees' order the pairs apart keep their place among the others: a
  // front's walk follows the recorded order when they come to overlap.
  struct ChildTest {
    std::uint32_t a, b;
    bool overlaps;
    double separation;
  };
  int orderedChildren(const Expansion& x, bool measure, ChildTest out[4]) {
    detail::PairKernel pairs = pairsOf(x);
    double separation[4] = {0.0, 0.0, 0.0, 0.0};
    unsigned mask = measure ? pairs.measure(separation) : pairs.boxAndSlabMask();
    mask &= ~pairs.apartByCells(mask);
    if (measure) keepCertainCells(pairs, mask, separation);
    const int count = x.countA * x.countB;
    work.nodePairs += static_cast<std::uint64_t>(count);
    // In the trees' order, last child first: each pair goes straight to its place.
    int k = count;
    for (int i = 0; i < x.countA; ++i) {
      for (int j = 0; j < x.countB; ++j) {
        const int p = detail::PairKernel::index(i, j);
        out[--k] = ChildTest{x.ca[i], x.cb[j], ((mask >> p) & 1u) != 0, separation[p]};
      }
    }
    if (deepestFirst && mask != 0) sortDeepestLast(pairs, x, out, count);
    return count;
  }

  // The cells are no distance. A pair they part keeps its boxes' measure, which certifies
  // nothing for a pair reported apart (a walk tests it again); an overlapping pair keeps its
  // certificate only where the cells still meet with the region shrunk by what it would
  // certify, so that a walk need not test the cells of a pair it trusts.
  void keepCertainCells(detail::PairKernel& pairs, unsigned overlapping, double separation[4]) {
    for (int p = 0; p < 4; ++p) {
      if (((overlapping >> p) & 1u) == 0) continue;
      const double held = -separation[p] - motion;
      if (held > 0.0 && pairs.apartByCellsWithin(1u << p, held) != 0) separation[p] = 0.0;
    }
  }

  // Deepest first: the pairs sorted by their boxes' overlap depth, the deepest last (the
  // stack pops it first); ties keep the trees' order. Pairs apart count as depth -1.
  static void sortDeepestLast(const detail::PairKernel& pairs, const Expansion& x,
                              ChildTest out[4], int count) {
    double depth[4];
    pairs.boxDepths(depth);
    ChildTest sorted[4];
    float key[4];  // ascending: the pop order is its reverse
    int n = 0;
    for (int i = 0; i < x.countA; ++i) {
      for (int j = 0; j < x.countB; ++j) {
        const ChildTest& t = out[count - 1 - (i * x.countB + j)];
        const float d =
            t.overlaps ? static_cast<float>(depth[detail::PairKernel::index(i, j)]) : -1.0f;
        insertAscending(sorted, key, n, t, d);
      }
    }
    for (int k = 0; k < count; ++k) out[k] = sorted[count - 1 - k];
  }

  // --- exact mode walking its front (QuerySettings::keepFront) ------------------------------
  // The depth-first descent of runExact, with each pair's box test answered by its
  // certificate where the motion has not used it up (traversal_front.h). A pair that was
  // expanded last time is walked through what lay below it; one that now overlaps and was
  // not is expanded as runExact would; what lay below a pair now apart is dropped. Pairs are
  // processed in the recorded order, and a fresh expansion orders its children as runExact
  // does: the hits, and so the witnesses, come in runExact's order.
  void runFront() {
    heap.clear();
    if (!started) beginWalk();
    while (!frames.empty()) {
      if (frames.back().hasPending) {
        if (!processPending()) return;
        continue;
      }
      WalkFrame& f = frames.back();
      detail::FrontEntry c{};
      bool overlaps = false;
      std::size_t begin = 0, end = 0;
      if (f.fromOld) {
        if (f.oldCursor >= f.oldEnd) {
          popFrame();
          continue;
        }
        c = front[f.oldCursor];
        begin = f.oldCursor + 1;
        end = begin + c.below;
        if (c.apart(reach)) {
          overlaps = false;
        } else if (c.overlapping(reach)) {
          overlaps = true;  // boxes and cells (keepCertainCells)
        } else {
          if (!budgetLeft(1)) {
            cutWalk();
            return;
          }
          overlaps = testPair(c);
        }
        f.oldCursor = end;
      } else {
        if (f.kidNext >= f.kidCount) {
          popFrame();
          continue;
        }
        overlaps = f.kidOverlaps[f.kidNext];
        c = f.kids[f.kidNext++];
      }
      ++fromScratch;
      if (!overlaps) {  // apart: what lay below it is dropped
        c.below = 0;
        record(c);
        continue;
      }
      const std::size_t at = record(c);
      const std::uint32_t region = childRegion(f.region, c.depthA, c.depthB);
      if (regionFull(region)) {  // skipped as runExact skips it; what lay below is kept
        ++work.pairsPopped;
        copyRecorded(begin, end);
        continue;
      }
      f.hasPending = true;
      f.pending = c;
      f.pendingAt = at;
      f.pendingRegion = region;
      f.pendingBegin = begin;
      f.pendingEnd = end;
    }
    closeWalk();
    finish(exactHit, 1.0, StopReason::Completed);
  }

  // The roots are always tested (as runExact tests them), unless their certificate holds.
  void beginWalk() {
    started = walkOpen = recording = true;
    nextFront.clear();
    frames.clear();
    frames.reserve(2 * static_cast<std::size_t>(a.maxDepth + b.maxDepth) + 4);
    fromScratch = 1;
    detail::FrontEntry root{0, 0, 0.0f, 0, 0, 0};
    if (!front.empty()) root = front.front();
    bool overlaps = root.overlapping(reach);
    if (!overlaps && !root.apart(reach)) overlaps = testPair(root);
    if (!overlaps) root.below = 0;
    const std::size_t at = record(root);
    if (!overlaps) return;  // no frames: the walk ends at once
    WalkFrame base;  // the roots' parent, holding them as its pending child
    base.hasPending = true;
    base.pending = root;
    base.pendingAt = at;
    base.pendingRegion = childRegion(kNoRegion, 0, 0);
    base.pendingBegin = std::min<std::size_t>(1, front.size());
    base.pendingEnd = front.empty() ? 0 : 1 + std::size_t{root.below};
    frames.push_back(base);
  }

  // The child waiting on the top frame: its leaf test, or its expansion (walked from what lay
  // below it, or fresh). Returns false when the walk stops here (a budget, or the answer).
  bool processPending() {
    WalkFrame& f = frames.back();
    const detail::FrontEntry c = f.pending;
    const std::uint32_t region = f.pendingRegion;
    if (a.tree->nodes()[c.a].isLeaf() && b.tree->nodes()[c.b].isLeaf()) {
      if (!budgetLeft()) {
        cutWalk();
        return false;
      }
      f.hasPending = false;
      ++work.pairsPopped;
      if (testLeaves(c.a, c.b, region)) {
        exactHit = true;
        if (hitEndsQuery()) {
          closeWalk();
          finish(true, 1.0, hitStop());
          return false;
        }
      }
      return true;
    }
    WalkFrame next;
    next.parentAt = f.pendingAt;
    next.region = region;
    if (f.pendingBegin < f.pendingEnd) {
      next.fromOld = true;
      next.oldCursor = f.pendingBegin;
      next.oldEnd = f.pendingEnd;
    } else {
      if (!budgetLeft()) {
        cutWalk();
        return false;
      }
      expandFresh(c, next);
    }
    f.hasPending = false;
    ++work.pairsPopped;
    frames.push_back(next);  // `f` is not used after this: the push may move it
    return true;
  }

  // runExact's expansion of a pair with nothing recorded below it: every child pair tested
  // and certified, processed in the order runExact pops them.
  void expandFresh(const detail::FrontEntry& c, WalkFrame& out) {
    const Expansion x = expand(c.a, c.depthA, c.b, c.depthB);
    ChildTest kids[4];
    const int count = orderedChildren(x, true, kids);
    out.kidCount = static_cast<std::uint8_t>(count);
    for (int k = 0; k < count; ++k) {
      out.kids[k] = detail::FrontEntry{kids[k].a, kids[k].b,
                                       certify(kids[k].overlaps, kids[k].separation),
                                       static_cast<std::uint8_t>(x.depthA),
                                       static_cast<std::uint8_t>(x.depthB), 0};
      out.kidOverlaps[k] = kids[k].overlaps;
    }
  }

  // The certificate of a pair just tested, counted from the front's reference pose: its
  // answer holds for any pose within |measured| - motion of the reference (stored with
  // `consumed` added). The answer is overlap()'s (runExact's, PairKernel::measure); a measure
  // that disagrees within rounding certifies nothing.
  float certify(bool overlaps, double separation) const {
    const double held = overlaps ? -separation - motion : separation - motion;
    if (!(held > 0.0)) return 0.0f;
    return detail::certificateOf(overlaps ? -(held + consumed) : held + consumed);
  }

  bool testPair(detail::FrontEntry& c) {
    ++work.nodePairs;
    double separation[4];
    detail::PairKernel pair(*a.tree, &c.a, 1, *b.tree, &c.b, 1, frame);
    unsigned mask = pair.measure(separation);
    mask &= ~pair.apartByCells(mask);
    keepCertainCells(pair, mask, separation);
    c.certificate = certify(mask != 0, separation[0]);
    return mask != 0;
  }

  // Appends an entry to the record; returns where it went.
  std::size_t record(const detail::FrontEntry& e) {
    if (!recording) return kNotRecorded;
    if (nextFront.size() + 1 >= detail::kMaxFrontEntries) {
      recording = false;  // too big to be worth keeping: the next query starts afresh
      return kNotRecorded;
    }
    nextFront.push_back(e);
    return nextFront.size() - 1;
  }

  // A frame whose children are all recorded: its parent's entry learns its subtree's size.
  void popFrame() {
    const std::size_t at = frames.back().parentAt;
    if (recording && at != kNotRecorded) {
      nextFront[at].below = static_cast<std::uint16_t>(nextFront.size() - at - 1);
    }
    frames.pop_back();
  }

  // Entries kept below a pair this walk did not descend (a full region, a stopped walk):
  // still true certificates, for a later walk that does.
  void copyRecorded(std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) record(front[i]);
  }

  // Ends the walk: what it did not reach is recorded as it was (each frame's pending child's
  // entries, then its remaining children with theirs, innermost frame first: the recorded
  // order), and the record becomes the front. The remaining children of frames the descent
  // had expanded count towards the from-roots cost (runExact tests them when it expands
  // their parent); nothing below them does.
  void closeWalk() {
    while (!frames.empty()) {
      WalkFrame& f = frames.back();
      if (f.hasPending) {
        // Recorded last, with its old size: what lay below it follows as it was.
        copyRecorded(f.pendingBegin, f.pendingEnd);
        f.hasPending = false;
      }
      if (f.fromOld) {
        copyRecorded(f.oldCursor, f.oldEnd);
        for (std::size_t i = f.oldCursor; i < f.oldEnd; i += 1 + std::size_t{front[i].below}) {
          ++fromScratch;
        }
      } else {
        for (; f.kidNext < f.kidCount; ++f.kidNext) {
          record(f.kids[f.kidNext]);
          ++fromScratch;
        }
      }
      popFrame();
    }
    if (recording) {
      front.swap(nextFront);
    } else {
      front.clear();
    }
    nextFront.clear();
    walkOpen = false;
    result.fromScratchNodePairs = fromScratch;
  }

  // A budget stopped the walk: its frames stay for the next step() of this query. The pairs
  // not proven apart that it has not reached are its open pairs, estimated as runExact's
  // stack is, and the front's entries it has not reached estimate the rest of the cost.
  void cutWalk() {
    heap.clear();
    std::size_t unreached = 0;
    for (std::size_t k = frames.size(); k-- > 0;) {
      const WalkFrame& f = frames[k];
      const std::uint32_t region = f.region;
      const auto open = [&](const detail::FrontEntry& e, std::uint32_t r) {
        heap.push_back(Entry{kUnestimated, 1.0f, e.a, e.b, r, e.depthA, e.depthB, 0.0f});
      };
      if (f.hasPending) open(f.pending, f.pendingRegion);
      if (f.fromOld) {
        if (unreached == 0) unreached = front.size() - f.oldCursor;
        for (std::size_t i = f.oldCursor; i < f.oldEnd; i += 1 + std::size_t{front[i].below}) {
          if (!front[i].apart(reach)) open(front[i], region);
        }
      } else {
        for (int i = f.kidNext; i < f.kidCount; ++i) {
          if (f.kidOverlaps[i]) open(f.kids[i], region);
        }
      }
    }
    result.fromScratchNodePairs = fromScratch + unreached;
    estimateFrontier();
    finish(exactHit, exactHit ? 1.0 : 1.0 - collisionProbability(evidence()), result.stop);
  }

  // --- ADB mode: the paper's priority traversal ----------------------------------------
  void push(const detail::PairEstimate& est, double key, std::uint32_t ia, std::uint32_t ib,
            std::uint32_t region, int da, int db) {
    const Entry e{static_cast<float>(key), static_cast<float>(doubtOf(est)), ia, ib, region,
                  static_cast<std::uint16_t>(da), static_cast<std::uint16_t>(db),
                  static_cast<float>(est.expected)};
    heap.push_back(e);
    std::push_heap(heap.begin(), heap.end(), heapLess);
  }

  // --- ADB mode with the table key ------------------------------------------------------
  // E[X] to 8 bits of mantissa (0.4 %), rounded down: the value a pair adds to the running
  // sums when pushed is the one it takes off when popped.
  static std::uint16_t encodeExpected(double expected) {
    if (!(expected > 0.0)) return 0;
    const float f = static_cast<float>(expected);
    std::uint32_t bits = 0;
    std::memcpy(&bits, &f, sizeof bits);
    return static_cast<std::uint16_t>(bits >> 15);  // the sign bit is 0
  }
  static double decodeExpected(std::uint16_t code) {
    const std::uint32_t bits = std::uint32_t{code} << 15;
    float f = 0.0f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
  }

  void pushQueue(std::uint32_t ia, std::uint32_t ib, std::uint32_t region, int da, int db,
                 double expected, int bucket, bool isBlind) {
    const QueueEntry e{ia, ib, region, static_cast<std::uint8_t>(da),
                       static_cast<std::uint8_t>(db), encodeExpected(expected)};
    const double x = decodeExpected(e.expected);
    openExpected += x;
    openDoubt += std::min(1.0, x);
    if (isBlind) {
      ++blindOpen;
      blindLogMiss += priorities->logMiss[bucket];
    }
    queue.push(e, bucket);
    openStale = true;
  }

  QueueEntry popQueue() {
    int bucket = 0;
    const QueueEntry e = queue.pop(bucket);
    forgetOpen(e, bucket);
    return e;
  }

  // Takes a pair that left the queue from `bucket` off the running sums (exactly 0 once it is
  // empty).
  void forgetOpen(const QueueEntry& e, int bucket) {
    openStale = true;
    if (queue.empty()) {
      openExpected = openDoubt = 0.0;
      blindOpen = 0;
      blindLogMiss = 0.0;
      return;
    }
    const double x = decodeExpected(e.expected);
    openExpected -= x;
    openDoubt -= std::min(1.0, x);
    if (blind(e.a, e.b)) {
      --blindOpen;
      blindLogMiss = blindOpen == 0 ? 0.0 : blindLogMiss - priorities->logMiss[bucket];
    }
  }

  // The first step of either key: the roots tested and estimated. False when they are apart
  // (the query is then answered).
  bool testRoots(detail::PairEstimate& root) {
    started = true;
    ++work.nodePairs;
    root = detail::estimatePair(a, 0, 0, b, 0, 0, frame);
    if (!root.overlap) finish(false, 1.0, StopReason::Completed);
    return root.overlap;
  }

  void runAdbTable() {
    if (!started) {
      detail::PairEstimate root;
      if (!testRoots(root)) return;
      pushQueue(0, 0, childRegion(kNoRegion, 0, 0), 0, 0, root.expected,
                detail::kPriorityBuckets - 1, blind(0, 0));
    }
    while (!queue.empty()) {
      if (!budgetLeft()) {
        finishUncertain(result.stop);
        return;
      }
      const QueueEntry e = popQueue();
      ++work.pairsPopped;
      if (!regionFull(e.region) && expandTable(e)) return;
    }
    finishUncertain(StopReason::Completed);
  }

  // expandAdb with the table key: the same pairs pruned and accepted (a pair's Eq. 3 > 0
  // exactly when both sides have a possible collision cell at a depth term > 0, and Eq. 3 is
  // evaluated wherever its pre-test says it could pass p_min); only the order differs.
  bool expandTable(const QueueEntry& e) {
    const Node& na = a.tree->nodes()[e.a];
    const Node& nb = b.tree->nodes()[e.b];
    if (na.isLeaf() && nb.isLeaf()) return testLeafPair(e.a, e.b, e.region);
    const Expansion x = expand(e.a, e.depthA, e.b, e.depthB);
    detail::PairKernel pairs = pairsOf(x);
    detail::CellCounts counts[4];
    const unsigned mask = pairs.overlapMaskAndCounts(counts);
    const DepthTerms& terms = depthTermsOf(x.depthA, x.depthB);
    const double lb = terms.lb;
    const int column = terms.column;
    const int passing = terms.passing;  // Eq. 3's pre-test, part 1
    for (int i = 0; i < x.countA; ++i) {
      for (int j = 0; j < x.countB; ++j) {
        ++work.nodePairs;  // counted up to the decision: an acceptance ends the expansion
        const int p = detail::PairKernel::index(i, j);
        if (((mask >> p) & 1u) == 0) continue;
        const detail::CellCounts& c = counts[p];
        const bool possible = c.sA > 0 && c.sB > 0 && lb > 0.0;
        if (!possible && settings.pruneImprobable) {  // paper: only p > 0
          notePruned(c.expected);
          continue;
        }
        const bool speaks = acceptable(x.ca[i], x.cb[j]);
        if (possible && speaks && std::min(c.sA, c.sB) >= passing &&
            collisionTailCouldExceed(c.s, c.sA, c.sB, passing, settings.pMin)) {
          const double eq3 = collisionLowerBound(c.s, c.sA, c.sB, lb);
          if (eq3 > settings.pMin && accept(x.ca[i], x.cb[j], eq3)) return true;
        }
        int bucket = possible ? detail::priorityBucket(*priorities,
                                                       static_cast<float>(c.expected), column)
                              : 0;
        if (!speaks) {
          bucket = std::max(bucket, detail::bucketOfProbability(
                                        blindKey(pairs.occupiedFill(i, j), x.ca[i], x.cb[j])));
        }
        pushQueue(x.ca[i], x.cb[j], childRegion(e.region, x.depthA, x.depthB), x.depthA,
                  x.depthB, c.expected, bucket, !speaks);
      }
    }
    return false;
  }

  const DepthTerms& depthTermsOf(int depthA, int depthB) {
    const std::size_t sum = static_cast<std::size_t>(depthA + depthB);
    DepthTerms& t = depthTerms[sum];
    if (t.passing < 0) {
      t.lb = cellIntersectionBound(depthA, depthB, a.maxDepth, b.maxDepth);
      t.column = detail::priorityColumn(t.lb);
      t.passing = smallestPassingCells(t.lb, settings.pMin);
    }
    return t;
  }

  // The open pairs of the table key's queue as OpenPairs, for openPairs(): each with its
  // bucket's key for p and min(1, E[X]) for its doubt.
  void mirrorQueue() {
    if (!openStale) return;
    heap.clear();
    queue.forEachBucket([this](const std::vector<QueueEntry>& entries, int bucket) {
      const float p = static_cast<float>(priorities->probability[bucket]);
      for (auto it = entries.rbegin(); it != entries.rend(); ++it) {  // pop order
        const float x = static_cast<float>(decodeExpected(it->expected));
        heap.push_back(Entry{p, std::min(1.0f, x), it->a, it->b, it->region, it->depthA,
                             it->depthB, x});
      }
    });
    openStale = false;
  }

  // Each open pair's fill (OpenPair::fill), for the ones not worked out since they were listed.
  void fillOpenPairs() {
    for (Entry& e : heap) {
      if (e.fill < 0.0f) e.fill = static_cast<float>(detail::pairFill(a, e.a, b, e.b, frame));
    }
  }

  Evidence queueEvidence() const {
    Evidence ev;
    double logMiss = 0.0;  // log prod (1 - p) over the open pairs
    queue.forEachBucket([&](const std::vector<QueueEntry>& entries, int bucket) {
      logMiss += static_cast<double>(entries.size()) * priorities->logMiss[bucket];
      ev.bestOpen = std::max(ev.bestOpen, priorities->probability[bucket]);
    });
    ev.frontierUnion = -std::expm1(logMiss);
    ev.frontierDoubt = std::max(0.0, openDoubt);
    ev.expectedCells = std::max(0.0, openExpected) + prunedExpected;
    ev.openPairs = static_cast<std::uint32_t>(std::min<std::size_t>(queue.size(), 0xFFFFFFFFu));
    ev.blindPairs = blindOpen;
    ev.blindUnion = std::clamp(-std::expm1(blindLogMiss), 0.0, 1.0);
    int filled = 0;
    queue.forEachBucketWhile([&](const std::vector<QueueEntry>& entries, int) {
      for (auto it = entries.rbegin(); it != entries.rend(); ++it) {  // pop order
        if (!addOpenFill(ev, it->a, it->b, filled)) return false;
      }
      return true;
    });
    commonEvidence(ev);
    return ev;
  }

  // The running sums over the queue worked out anew, after pairs left it other than by pop.
  void recountOpen() {
    openStale = true;
    openExpected = openDoubt = blindLogMiss = 0.0;
    blindOpen = 0;
    queue.forEachBucket([this](const std::vector<QueueEntry>& entries, int bucket) {
      for (const QueueEntry& e : entries) {
        const double x = decodeExpected(e.expected);
        openExpected += x;
        openDoubt += std::min(1.0, x);
        if (blind(e.a, e.b)) {
          ++blindOpen;
          blindLogMiss += priorities->logMiss[bucket];
        }
      }
    });
  }

  // --- ADB mode with the Eq. 3 key --------------------------------------------------------
  void runAdb() {
    if (!started) {
      detail::PairEstimate root;
      if (!testRoots(root)) return;
      // The paper inserts the roots with probability 1 so that they are expanded first; alone
      // in the queue they are popped first anyway, and the evidence needs their estimate
      // (Eq. 3 is 0 at depth 0, where LB = 0).
      heap.push_back(Entry{static_cast<float>(root.lower), static_cast<float>(doubtOf(root)), 0, 0,
                           childRegion(kNoRegion, 0, 0), 0, 0,
                           static_cast<float>(root.expected)});
    }
    while (!heap.empty()) {
      if (!budgetLeft()) {
        finishUncertain(result.stop);
        return;
      }
      std::pop_heap(heap.begin(), heap.end(), heapLess);
      const Entry e = heap.back();
      heap.pop_back();
      ++work.pairsPopped;
      if (!regionFull(e.region) && expandAdb(e)) return;
    }
    finishUncertain(StopReason::Completed);
  }

  // Expands one popped pair. Returns true when the query is decided.
  bool expandAdb(const Entry& e) {
    if (bothLeaves(e)) return testLeafPair(e.a, e.b, e.region);
    const Expansion x = expand(e.a, e.depthA, e.b, e.depthB);
    detail::PairKernel pairs = pairsOf(x);
    const unsigned mask = pairs.overlapMask();
    detail::CellCounts counts[4];
    if (mask != 0) pairs.cellCounts(mask, counts);
    for (int i = 0; i < x.countA; ++i) {
      for (int j = 0; j < x.countB; ++j) {
        ++work.nodePairs;  // counted up to the decision: an acceptance ends the expansion
        const int p = detail::PairKernel::index(i, j);
        if (((mask >> p) & 1u) == 0) continue;
        const detail::PairEstimate est = detail::estimateOverlapping(
            counts[p], x.depthA, x.depthB, a.maxDepth, b.maxDepth);
        if (!(est.lower > 0.0) && settings.pruneImprobable) {  // paper: only p > 0
          notePruned(est.expected);
          continue;
        }
        const bool speaks = acceptable(x.ca[i], x.cb[j]);
        if (est.lower > settings.pMin && speaks && accept(x.ca[i], x.cb[j], est.lower)) {
          return true;
        }
        const double key =
            speaks ? est.lower
                   : std::max(est.lower, blindKey(pairs.occupiedFill(i, j), x.ca[i], x.cb[j]));
        push(est, key, x.ca[i], x.cb[j], childRegion(e.region, x.depthA, x.depthB), x.depthA,
             x.depthB);
      }
    }
    return false;
  }

  // A leaf pair popped in ADB mode: its triangles decide. Returns true when the query is.
  bool testLeafPair(std::uint32_t ia, std::uint32_t ib, std::uint32_t region) {
    if (!testLeaves(ia, ib, region)) return false;
    exactHit = true;
    if (!hitEndsQuery()) return false;  // (stopAtFirstHit: no region fills)
    finish(true, 1.0, hitStop());
    return true;
  }

  // Whether a pair may be accepted on probability: not two leaves (their triangles decide),
  // and each node with enough triangles, not slivers, for the model to hold
  // (minTrianglesToAccept, kSliverFatness).
  bool acceptable(std::uint32_t ia, std::uint32_t ib) const {
    if (a.tree->nodes()[ia].isLeaf() && b.tree->nodes()[ib].isLeaf()) return false;
    const NodeOccupancy& oa = a.tree->occupancy()[ia];
    const NodeOccupancy& ob = b.tree->occupancy()[ib];
    if (settings.minTrianglesToAccept > 0 && (oa.slivers || ob.slivers)) return false;
    return std::min<int>(oa.triangles, ob.triangles) >= settings.minTrianglesToAccept;
  }

  // Whether the cell model is blind to a pair: it may not be accepted on probability (a leaf
  // pair, a node of few triangles or of slivers), and its E[X] says little either way.
  bool blind(std::uint32_t ia, std::uint32_t ib) const { return !acceptable(ia, ib); }

  // The priority key of a blind pair whose nodes are `fill` full where they meet
  // (PairKernel::occupiedFill): the fill, discounted by the triangles that resolving the pair
  // may take (kCheapBlindTriangles).
  double blindKey(double fill, std::uint32_t ia, std::uint32_t ib) const {
    const double triangles = static_cast<double>(a.tree->occupancy()[ia].triangles) +
                             static_cast<double>(b.tree->occupancy()[ib].triangles);
    return fill * std::min(1.0, kCheapBlindTriangles / std::max(1.0, triangles));
  }

  // The roots' fill, worked out once per query and only where a stop needs evidence (a query
  // that completes pays nothing for it).
  double rootsFill() const {
    if (rootFill < 0.0) rootFill = detail::pairFill(a, 0, b, 0, frame);
    return rootFill;
  }

  // Adds one open pair's fill to the evidence: true while more are wanted.
  bool addOpenFill(Evidence& ev, std::uint32_t ia, std::uint32_t ib, int& filled) const {
    const double fill = detail::pairFill(a, ia, b, ib, frame);
    ev.openFillUnion = 1.0 - (1.0 - ev.openFillUnion) * (1.0 - fill);
    ev.openFillMax = std::max(ev.openFillMax, fill);
    return ++filled < kFilledOpenPairs;
  }

  // The evidence every key and mode shares: what was accepted, pruned and done.
  void commonEvidence(Evidence& ev) const {
    ev.prunedDoubt = prunedMass;
    ev.collisionPairs = result.collisionPairs;
    ev.rootFill = rootsFill();
    ev.nodePairs = result.nodePairs + (inStep ? work.nodePairs : 0);
  }

  // A collision pair (p > p_min). Returns true when it is the k_min-th: the query is decided.
  bool accept(std::uint32_t ia, std::uint32_t ib, double p) {
    ++result.collisionPairs;
    if (settings.nodeWitnesses) {
      Witness w;
      w.nodeA = ia;
      w.nodeB = ib;
      w.probability = static_cast<float>(p);
      addWitness(w);
    }
    if (result.collisionPairs < static_cast<std::uint32_t>(settings.kMin)) return false;
    finishUncertain(StopReason::QualityReached);
    return true;
  }

  // The answer of an ADB query that stopped without an exact hit deciding it: certain when
  // nothing was left or pruned, else the more probable side under the fitted estimate, which
  // at k_min or a queue emptied by pruning is the probability that the paper's answer is
  // right (collision_estimate.h). Witnesses (accepted pairs) are shown for a "collision".
  void finishUncertain(StopReason why) {
    dropFullRegionsFromHeap();
    double p = 0.0;  // P(collision)
    if (exactHit) {
      p = 1.0;
    } else if (openCount() > 0 || prunedMass > 0.0 || why == StopReason::QualityReached) {
      Evidence ev = evidence();
      ev.quality = !isBudgetStop(why);
      ev.reachedKMin = why == StopReason::QualityReached;
      p = collisionProbability(ev);
    }
    const bool collides = p >= 0.5;
    finish(collides, collides ? p : 1.0 - p, why);
  }

  std::size_t openCount() const { return tableKey ? queue.size() : heap.size(); }

  Evidence evidence() const {
    if (tableKey) return queueEvidence();
    Evidence ev;
    double miss = 1.0;       // prod (1 - p) over the open pairs
    double blindMiss = 1.0;  // the same over the blind ones
    for (const Entry& e : heap) {
      miss *= 1.0 - static_cast<double>(e.p);
      ev.frontierDoubt += e.upper;
      ev.bestOpen = std::max(ev.bestOpen, static_cast<double>(e.p));
      ev.expectedCells += e.expected;
      if (blind(e.a, e.b)) {
        ++ev.blindPairs;
        blindMiss *= 1.0 - static_cast<double>(e.p);
      }
    }
    // The heap's first entries are its largest keys (an exact mode stack's last, its next).
    int filled = 0;
    for (std::size_t k = 0; k < heap.size(); ++k) {
      const Entry& e = heap[settings.mode == QueryMode::Adb ? k : heap.size() - 1 - k];
      if (!addOpenFill(ev, e.a, e.b, filled)) break;
    }
    ev.expectedCells += prunedExpected;
    ev.frontierUnion = 1.0 - miss;
    ev.blindUnion = 1.0 - blindMiss;
    ev.openPairs = static_cast<std::uint32_t>(std::min<std::size_t>(heap.size(), 0xFFFFFFFFu));
    commonEvidence(ev);
    return ev;
  }

  // Pairs of regions whose hits were found are resolved, not open: a cut query leaves only
  // the others in openPairs(). The order of the rest is kept (exact mode resumes from it).
  // Returns whether any was dropped.
  bool dropFullRegions() {
    if (regionHits.empty()) return false;
    const auto full = [this](const Entry& e) { return regionFull(e.region); };
    const auto end = std::remove_if(heap.begin(), heap.end(), full);
    const bool dropped = end != heap.end();
    heap.erase(end, heap.end());
    return dropped;
  }

  // ADB mode: drops resolved regions and keeps the queue a heap. Only rebuilt where something
  // was dropped: make_heap may reorder equal priorities, so a query run in steps pops in the
  // same order as one run at once unless regions (contact sampling) were dropped on the way.
  void dropFullRegionsFromHeap() {
    if (tableKey) {
      if (regionHits.empty()) return;
      queue.removeIf([this](const QueueEntry& e) { return regionFull(e.region); });
      recountOpen();
      return;
    }
    if (dropFullRegions()) std::make_heap(heap.begin(), heap.end(), heapLess);
  }

  // Exact mode cut by a budget: the model's estimates for the pairs left on the stack (at
  // most 3 per level of depth, not counted as node pairs). Only the pairs pushed since the
  // last stop: a query resumed step after step keeps the bottom of its stack, estimated.
  void estimateFrontier() {
    dropFullRegions();
    for (Entry& e : heap) {
      if (e.p != kUnestimated) continue;
      const detail::PairEstimate est =
          detail::estimatePair(a, e.a, e.depthA, b, e.b, e.depthB, frame);
      e.p = static_cast<float>(
          blind(e.a, e.b) ? std::max(est.lower, blindKey(detail::pairFill(a, e.a, b, e.b, frame),
                                                          e.a, e.b))
                          : est.lower);
      e.upper = static_cast<float>(doubtOf(est));
      e.expected = static_cast<float>(est.expected);
    }
  }

  void finish(bool collides, double confidence, StopReason why) {
    result.collides = collides;
    result.confidence = std::clamp(confidence, 0.0, 1.0);
    result.stop = why;
  }
};

Traversal::Traversal() : m_impl(std::make_unique<Impl>()) {}

Traversal::Traversal(const AdbTree& a, const Pose& poseA, const AdbTree& b, const Pose& poseB,
                     const QuerySettings& settings)
    : Traversal() {
  reset(a, poseA, b, poseB, settings);
}

Traversal::~Traversal() = default;
Traversal::Traversal(Traversal&&) noexcept = default;
Traversal& Traversal::operator=(Traversal&&) noexcept = default;

void Traversal::reset(const AdbTree& a, const Pose& poseA, const AdbTree& b, const Pose& poseB,
                      const QuerySettings& settings) {
  m_impl->reset(a, poseA, b, poseB, settings);
}

const QueryResult& Traversal::step(const StepBudget& budget) { return m_impl->step(budget); }
bool Traversal::done() const { return m_impl->finished; }
const QueryResult& Traversal::result() const { return m_impl->result; }
const StepWork& Traversal::lastStep() const { return m_impl->work; }
const std::vector<OpenPair>& Traversal::openPairs() const {
  m_impl->mirrorQueue();
  m_impl->fillOpenPairs();
  return m_impl->heap;
}
const std::vector<Witness>& Traversal::witnesses() const {
  static const std::vector<Witness> kNone;
  return m_impl->result.collides ? m_impl->witnesses : kNone;
}
Evidence Traversal::evidence() const { return m_impl->evidence(); }

std::size_t Traversal::capacityBytes() const {
  const Impl& m = *m_impl;
  return m.heap.capacity() * sizeof(Entry) + m.stack.capacity() * sizeof(Impl::StackEntry) +
         m.queue.capacityBytes() + m.depthTerms.capacity() * sizeof(Impl::DepthTerms) +
         m.witnesses.capacity() * sizeof(Witness) +
         m.regionHits.capacity() * sizeof(std::uint32_t) +
         (m.front.capacity() + m.nextFront.capacity()) * sizeof(detail::FrontEntry) +
         m.frames.capacity() * sizeof(Impl::WalkFrame);
}

bool isBudgetStop(StopReason r) {
  return r == StopReason::TimeBudget || r == StopReason::WorkBudget;
}

const char* toString(StopReason r) {
  switch (r) {
    case StopReason::Completed: return "completed";
    case StopReason::QualityReached: return "quality reached";
    case StopReason::ExactHit: return "exact hit";
    case StopReason::WitnessesFull: return "witnesses full";
    case StopReason::TimeBudget: return "time budget";
    case StopReason::WorkBudget: return "work budget";
  }
  return "unknown";
}

void validate(const QuerySettings& s) {
  if (!(s.pMin >= 0.0 && s.pMin <= 1.0)) {
    throw SettingsError("QuerySettings::pMin is " + detail::formatNumber(s.pMin) +
                        "; it must be in [0, 1]");
  }
  if (s.minTrianglesToAccept < 0 || s.minTrianglesToAccept > 127) {
    throw SettingsError("QuerySettings::minTrianglesToAccept is " +
                        std::to_string(s.minTrianglesToAccept) + "; it must be in 0..127");
  }
  if (s.kMin < 1) {
    throw SettingsError("QuerySettings::kMin is " + std::to_string(s.kMin) +
                        "; it must be at least 1");
  }
  if (s.regionDepth < 0) {
    throw SettingsError("QuerySettings::regionDepth is " + std::to_string(s.regionDepth) +
                        "; it must be >= 0");
  }
  if (!(std::isfinite(s.contactMargin) && s.contactMargin >= 0.0)) {
    throw SettingsError("QuerySettings::contactMargin is " +
                        detail::formatNumber(s.contactMargin) + "; it must be finite and >= 0");
  }
  if (std::isnan(s.budgetMicros) || s.budgetMicros < 0.0) {
    throw SettingsError("QuerySettings::budgetMicros is " + detail::formatNumber(s.budgetMicros) +
                        "; it must be >= 0 (infinity for no budget)");
  }
}

QueryResult collide(const AdbTree& a, const Pose& poseA, const AdbTree& b, const Pose& poseB,
                    const QuerySettings& settings, QueryScratch& scratch) {
  Traversal& t = scratch.m_traversal;
  QuerySettings once = settings;
  once.keepFront = false;  // a scratch serves any pair of trees: nothing to carry
  t.reset(a, poseA, b, poseB, once);
  return t.step(StepBudget{settings.budgetNodePairs, settings.budgetMicros});
}

}  // namespace adb
