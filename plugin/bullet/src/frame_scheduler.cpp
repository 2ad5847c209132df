// FrameScheduler: the policy that spends one step's budget across its adb pairs, then writes
// their contacts. What the work costs is FrameCostModel's, what the step did is counted by
// frame_statistics.h.
#include "frame_scheduler.h"

#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletDynamics/Dynamics/btRigidBody.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "adb/bullet/mesh_shape.h"
#include "conversions.h"
#include "frame_statistics.h"
#include "manifold_algorithm.h"
#include "mesh_mesh_algorithm.h"

namespace adb::detail {
namespace {

// The smallest first grant (kFirstGrant, frame_cost_model.h): a few levels of both trees.
// Smaller grants would mostly need a second query; larger ones starve the other pairs of a
// tight budget.
// A refinement gets at least this many node pairs more: doubling from tiny grants would
// spend the step on the queries' fixed costs (and, best first, on restarts).
constexpr std::uint64_t kMinGrowth = 64;
constexpr std::uint64_t kUnlimited = std::numeric_limits<std::uint64_t>::max();
// Mesh-mesh queries per round: their grants are decided together, before any of them runs,
// so that a node-pair budget gives the same simulation at any thread count. It is fixed (not
// the thread count) for that reason: enough queries of uneven cost to keep up to 16 threads
// busy, few enough that what a round's queries leave unused soon reaches the next round (one
// query per round is the serial schedule). Swept over 1 to 64 on the resting-tori scene of
// BudgetAllPairs in float and double and on the 50-body pile at 1/2 to 1/8 of the need
// (docs/bullet-results.md): no size lost a body or settled worse than the serial schedule;
// the tori's outcomes vary from size to size as a chaotic pile's do.
constexpr std::size_t kRoundPairs = 16;

std::uint64_t saturatingAdd(std::uint64_t a, std::uint64_t b) {
  return b <= kUnlimited - a ? a + b : kUnlimited;
}
// Steps a whole pair that costs more than the whole budget may be skipped in a row before it
// runs regardless: two kept steps hold a resting body; a budget smaller than one pair
// overruns by that pair every third step rather than letting the body fall.
constexpr std::uint64_t kMaxSkippedSteps = 2;
// Steps after the budget was last reached during which the policy keeps economising (the
// estimates decide shares, starved descents and resting pairs): a pile whose need hovers
// about the budget does not switch policy every other step; a budget never reached never
// economises, and gives the unbudgeted simulation.
constexpr std::uint64_t kReachedSteps = 60;
// A quality target needs the paper's best-first traversal; contacts alone are found faster
// depth first (docs/bullet-budget.md).
bool bestFirst(const FrameSettings& s) { return s.kMin > 0; }

// A pair with a static or kinematic body: the world holds the other body up.
bool anchored(const DeferredPair& p) {
  return p.object0->isStaticOrKinematicObject() || p.object1->isStaticOrKinematicObject();
}

// How far body 1 moves against body 0 in a step of `timeStep` at their linear velocities, in
// world axes (zero for bodies without velocities, or velocities too large to be finite).
btVector3 approachInStep(const DeferredPair& p, btScalar timeStep) {
  const auto velocity = [](const btCollisionObject* object) {
    const btRigidBody* body = btRigidBody::upcast(object);
    return body ? body->getLinearVelocity() : btVector3(0, 0, 0);
  };
  const btVector3 approach = (velocity(p.object1) - velocity(p.object0)) * timeStep;
  return std::isfinite(approach.length2()) ? approach : btVector3(0, 0, 0);
}

// Whether a pair with the world holds its body up: its last contacts push the body within
// 60 degrees of straight up against the body's gravity (a floor, not a wall beside it).
bool holdsUp(const DeferredPair& p) {
  if (!anchored(p) || !p.algorithm->holdsContacts()) return false;
  const bool bodyIs0 = !p.object0->isStaticOrKinematicObject();
  const btRigidBody* body = btRigidBody::upcast(bodyIs0 ? p.object0 : p.object1);
  if (body == nullptr) return false;
  const btVector3 up = -body->getGravity();
  const btVector3 normals = p.algorithm->lastNormalsOnB();  // on body 1, towards body 0
  const btVector3 push = bodyIs0 ? normals : -normals;
  return push.dot(up) > btScalar(0.5) * push.length() * up.length();
}

bool unbudgeted(const FrameSettings& s) {
  return s.budgetNodePairs == kUnlimited && std::isinf(s.budgetMicros);
}

// Whether mesh-mesh queries walk the fronts they keep (QuerySettings::keepFront): the same
// contacts as a descent from the roots for fewer node pairs, but more time per node pair
// (FrameSettings::fronts), so by default where node pairs are what the budget spends.
bool keepsFronts(const FrameSettings& s) {
  using Fronts = FrameSettings::Fronts;
  return s.fronts == Fronts::Always ||
         (s.fronts == Fronts::WithNodePairBudget && s.budgetNodePairs != kUnlimited);
}

// Doubt left in a cut query: Pr[X >= 1] summed over its unresolved node pairs (an upper
// bound on the chance that one of them holds an intersecting triangle pair).
double doubtOf(const std::vector<OpenPair>& open) {
  double doubt = 0.0;
  for (const OpenPair& o : open) doubt += static_cast<double>(o.upper);
  return std::min(1.0, doubt);
}

}  // namespace

MeshMeshAlgorithm& DeferredPair::meshMesh() const {
  return static_cast<MeshMeshAlgorithm&>(*algorithm);
}

PairWrappers::PairWrappers(const DeferredPair& pair)
    : body0(nullptr, pair.shape0, pair.object0, pair.transform0, pair.partId0, pair.index0),
      body1(nullptr, pair.shape1, pair.object1, pair.transform1, pair.partId1, pair.index1) {}

void FrameScheduler::begin() {
  ++m_step;
  m_pairs.clear();
  m_wholes.clear();
  m_badBodies.clear();
  m_badNamed = 0;
  m_collecting = true;
}

void FrameScheduler::defer(ManifoldAlgorithm* algorithm, const btCollisionObjectWrapper* body0,
                           const btCollisionObjectWrapper* body1) {
  DeferredPair pair{algorithm,
                    body0->getCollisionObject(),
                    body1->getCollisionObject(),
                    body0->getCollisionShape(),
                    body1->getCollisionShape(),
                    body0->getWorldTransform(),
                    body1->getWorldTransform(),
                    body0->m_partId,
                    body0->m_index,
                    body1->m_partId,
                    body1->m_index,
                    static_cast<std::uint32_t>(m_pairs.size() + m_wholes.size())};
  (algorithm->refinable() ? m_pairs : m_wholes).push_back(pair);
}

void FrameScheduler::noteBadPose(const btCollisionObject* body, PoseDefect defect) {
  if (std::find(m_badBodies.begin(), m_badBodies.end(), body) != m_badBodies.end()) return;
  m_badBodies.push_back(body);
  const BadPose bad{body, body->getWorldArrayIndex(), body->getUserPointer(), defect};
  if (m_badNamed < FrameStats::kNamedBadPoses) m_badNamedPoses[m_badNamed++] = bad;
  if (!m_badPoseCallback) return;
  // The callback may query the world (contactTest): its pairs must be answered at once, not
  // deferred into this step (Bullet frees contactTest's algorithms when it returns).
  const bool collecting = m_collecting;
  m_collecting = false;
  try {
    m_badPoseCallback(bad);
  } catch (...) {
    // Nothing may leave Bullet's step; the body is named in FrameStats all the same.
  }
  m_collecting = collecting;
}

void FrameScheduler::run(const FrameSettings& settings, const btDispatcherInfo& info) {
  m_collecting = false;
  m_info = &info;
  m_start = Clock::now();
  m_stats = FrameStats{};
  m_pool.configure(settings.threads);
  m_stats.threads = static_cast<std::uint32_t>(m_pool.threads());
  m_stats.pairs = static_cast<std::uint32_t>(m_pairs.size());
  m_stats.badPoseBodies = static_cast<std::uint32_t>(m_badBodies.size());
  std::copy(m_badNamedPoses, m_badNamedPoses + m_badNamed, m_stats.badPoses);
  m_unqueried = m_pairs.size();
  m_undecided = 0;
  m_stats.otherPairs = static_cast<std::uint32_t>(m_wholes.size());
  // Whole pairs run in the order of how far their bodies moved since they last ran (never
  // run first): a skipped pair keeps its last contacts, true only while its bodies barely
  // move. Pairs that run whatever the budget go before all (urgency): run last they overran
  // it. Ties (resting bodies) keep the dispatch's order, so that node-pair budgets stay
  // reproducible (std::sort: stable_sort would allocate).
  for (DeferredPair& pair : m_wholes) {
    pair.motion = pair.algorithm->motionSinceLastRun(pair.transform0, pair.transform1);
  }
  noteSupported();
  for (DeferredPair& pair : m_wholes) pair.urgency = urgency(pair);
  std::sort(m_wholes.begin(), m_wholes.end(), [](const DeferredPair& x, const DeferredPair& y) {
    if (x.urgency != y.urgency) return x.urgency < y.urgency;
    if (x.motion != y.motion) return x.motion > y.motion;
    const std::uint64_t rx = x.algorithm->lastRun(), ry = y.algorithm->lastRun();
    return rx != ry ? rx < ry : x.sequence < y.sequence;
  });
  if (settings.keepRestingContacts) keepRestingContacts();
  m_reachedLately = !unbudgeted(settings) && m_lastReached != 0 &&
                    m_step - m_lastReached <= kReachedSteps;
  m_binding = binding(settings);
  gatherWholes(settings);
  firstPass(settings);
  refine(settings);
  writeContacts(settings);
  keepSkipped();
  if (reachedBudget(settings)) m_lastReached = m_step;
  m_stats.micros = std::chrono::duration<double, std::micro>(Clock::now() - m_start).count();
  m_costs.updateMargin(m_stats.micros, settings.budgetMicros);
  // After the step's contacts are written and its time measured: the audit changes neither.
  m_audited.clear();
  if (settings.auditContacts) auditContacts(settings);
}

void FrameScheduler::auditContacts(const FrameSettings& settings) {
  const Clock::time_point start = Clock::now();
  if (!m_audit) m_audit = std::make_unique<ContactAudit>();
  ContactAuditStats& audit = m_stats.audit;
  audit.on = true;
  for (const DeferredPair& pair : m_pairs) {
    // The pairs that got plausible contacts: written this step from a query the budget cut
    // or that stopped on quality. A cut pair a time budget left no time to write is not
    // written: it kept last step's contacts.
    const bool plausible = isBudgetStop(pair.stop) || pair.stop == StopReason::QualityReached;
    if (!pair.written || !plausible) continue;
    const MeshMeshAlgorithm& algorithm = pair.meshMesh();
    const auto& mesh0 = static_cast<const MeshShape&>(*pair.shape0);
    const auto& mesh1 = static_cast<const MeshShape&>(*pair.shape1);
    ContactAudit::PairEvidence evidence;
    evidence.posed = PosedPair{&mesh0.tree(),       toPose(pair.transform0),
                               &mesh1.tree(),       toPose(pair.transform1),
                               mesh0.data().facing, mesh1.data().facing};
    evidence.found = &algorithm.witnesses();
    evidence.open = &algorithm.openPairs();
    evidence.margin = algorithm.contactMargin();
    evidence.threshold =
        std::max(evidence.margin, static_cast<double>(algorithm.breakingThreshold()));
    evidence.body0 = pair.object0;
    evidence.body1 = pair.object1;
    m_audit->audit(evidence, settings, audit, m_audited);
  }
  audit.micros = std::chrono::duration<double, std::micro>(Clock::now() - start).count();
}

std::uint64_t FrameScheduler::nodePairsLeft(const FrameSettings& s) const {
  if (s.budgetNodePairs == kUnlimited) return kUnlimited;
  return s.budgetNodePairs > m_stats.nodePairs ? s.budgetNodePairs - m_stats.nodePairs : 0;
}

double FrameScheduler::elapsedMicros() const {
  return std::chrono::duration<double, std::micro>(Clock::now() - m_start).count();
}

double FrameScheduler::microsLeft(const FrameSettings& s, bool holdBackWrites) const {
  if (std::isinf(s.budgetMicros)) return s.budgetMicros;
  const double used = elapsedMicros();
  // The contact writing still to come is part of the step: its expected cost is held back.
  // A pair not queried yet will most likely be decided and written at once; one the budget
  // cut is written at the end, and costs more (more witnesses, its plausible contacts).
  const double contacts =
      holdBackWrites ? m_costs.writeMicros() * static_cast<double>(m_unqueried) +
                           m_costs.lateWriteMicros() * static_cast<double>(m_undecided)
                     : 0.0;
  return std::max(0.0, s.budgetMicros - m_costs.margin(s.budgetMicros) - contacts - used);
}

// A query's time cap among `waiting` pairs of a time budget with `micros` left: an even
// share of the threads' time until the budget was reached lately (a cap, not a grant: a
// query within it runs as without a budget), then all that is left (the grant shares it).
double FrameScheduler::timeShare(double micros, std::uint64_t waiting) const {
  if (std::isinf(micros) || m_reachedLately || waiting == 0) return micros;
  return micros * static_cast<double>(m_pool.threads()) / static_cast<double>(waiting);
}

bool FrameScheduler::reachedBudget(const FrameSettings& settings) const {
  if (unbudgeted(settings)) return false;
  return m_stats.cutPairs > 0 || m_stats.lateKeptPairs > 0 || m_stats.otherKeptPairs > 0;
}

// A pair's even share of what is left, in node pairs. A time budget is shared as node pairs
// through the measured cost of one: a query given a tiny time share would overshoot it by a
// whole clock interval (the traversal reads the clock every 64 units of work), and hundreds
// of pairs would overshoot the step by hundreds of intervals. The pool's threads work
// through node pairs side by side, so a time budget covers as many times more of them
// (what one query may take stays capped by the round's deadline). Only once the budget was
// reached lately: until then a time budget is no grant, only each query's time cap
// (timeShare), and a budget the step never reaches leaves every query as it would run
// without one.
std::uint64_t FrameScheduler::share(const FrameSettings& s, std::uint64_t waiting,
                                    std::uint64_t reserved, double micros) const {
  std::uint64_t left = nodePairsLeft(s);
  if (left != kUnlimited) left = (left > reserved ? left - reserved : 0) / waiting;
  if (!std::isinf(micros) && m_reachedLately) {
    const double lanes = static_cast<double>(m_pool.threads());
    const double byTime =
        (micros * lanes / m_costs.microsPerNodePair() - static_cast<double>(reserved)) /
        static_cast<double>(waiting);
    left = std::min(left, static_cast<std::uint64_t>(std::clamp(byTime, 0.0, 1e18)));
  }
  return left;
}

// The traversal of one query. It reads the settings and the pair's trees and writes only the
// pair's own traversal, so the queries of different pairs may run on different threads.
void FrameScheduler::traverse(DeferredPair& pair, const QueryRequest& request,
                              const FrameSettings& settings) {
  QuerySettings q;
  if (bestFirst(settings) && !request.whole) {  // a whole query is an exact one
    q.mode = QueryMode::Adb;
    q.pMin = settings.pMin;
    q.kMin = settings.kMin;
    q.pruneImprobable = false;  // complete means exact; cut leaves every open pair
    q.nodeWitnesses = false;    // the 64 witness slots are for triangle pairs
    // A cut pair's open pairs become plausible contacts by their calibrated probability
    // (openPairProbability: >= pAccept, softer the lower), which reads each pair's key p:
    // Eq. 3 itself, not the table key's bucket (9 % wide).
    q.adbKey = AdbKey::Eq3;
  } else {
    q.mode = QueryMode::Exact;
    // A pair the budget is about to cut (granted less than it wants) or cut last step
    // descends its deepest overlaps first, so that a cut descent has seen the contacts that
    // keep bodies apart (FrameBudget.ABindingBudgetKeepsEveryBodyOnTheGround: with the
    // trees' order a body went 0.086 into the ground, more than the test allows). The
    // others keep the trees' order: a budget that never cuts a pair changes nothing (the
    // same simulation as no budget), and resting contacts sample the same triangle pairs
    // step after step.
    // A fast pair's speculative query, too: it keeps the closest near pairs and shrinks its
    // margin to the farthest kept once it holds them (a branch and bound on distance), so
    // the nearest boxes go first. In the trees' order the margin shrank slowly: the bunny
    // at 200 m/s onto a 4 cm mesh slab took 11,299 node pairs (12 to 77 ms) at its impact
    // step, nearest first 465 (0.3 ms; the scene and command: docs/bullet-budget.md,
    // "Continuous collision detection").
    const bool speculating = pair.meshMesh().contactMargin() > 0.0;
    q.descent = request.starved || pair.meshMesh().cut() || speculating
                    ? ExactDescent::DeepestFirst
                    : ExactDescent::TreeOrder;
  }
  // Exact mode only: the core ignores it otherwise. Not for a sweeping pair's query: its
  // margin (the distance the bodies close in the step) changes every step, which restarts a
  // front anyway, and walking one keeps the margin from shrinking to the closest pairs found
  // (a robot arm falling into the room took 188,000 node pairs, 320 ms, in one step).
  q.keepFront = keepsFronts(settings) && !request.whole;
  StepBudget budget;
  if (!unbudgeted(settings)) budget = StepBudget{request.grant, request.micros};
  pair.meshMesh().query(pair, q, budget, request.resume);
}

// What a query did, counted on the calling thread in pair order: the cost model, the step's
// statistics and the pair's scheduling state. Returns the work it did (node pairs, triangle
// tests and pairs popped).
std::uint64_t FrameScheduler::account(DeferredPair& pair, const QueryRequest& request) {
  const QueryResult& r = pair.meshMesh().result();
  const StepWork& work = pair.meshMesh().lastStep();
  m_costs.measureQuery(work.nodePairs, work.seconds);
  // Total granted this step: a resumed query adds to what it had.
  const std::uint64_t grant = request.grant;
  if (!request.resume) {
    pair.grant = grant;
  } else {
    pair.grant = saturatingAdd(pair.grant, grant);
  }
  pair.stop = r.stop;
  ++m_stats.queries;
  m_stats.nodePairs += work.nodePairs;
  if (request.whole) {
    ++m_stats.mustRunPairs;
    m_stats.mustRunNodePairs += work.nodePairs;
  }
  pair.confidence = r.confidence;  // 1 when decided exactly or after a hit
  switch (r.stop) {
    case StopReason::Completed:
    case StopReason::WitnessesFull:  // its contacts are what a completed query would give
      pair.completeness = 1.0;
      break;
    case StopReason::QualityReached:
      pair.completeness = r.confidence;
      break;
    default:
      pair.completeness = 1.0 - doubtOf(pair.meshMesh().openPairs());
      break;
  }
  // Leaf pairs cost triangle tests, not node pairs, and some popped pairs cost neither: all
  // are progress.
  return work.nodePairs + work.triangleTests + work.pairsPopped;
}

// Whether the budget is too small for every pair's expected cost, once it has been reached
// lately: only then may a resting pair keep its contacts. The estimates alone (each pair's
// last cost and a quarter more, times the measured time per node pair) bind a budget the
// step would not reach: 9 bodies on a mesh ground under a 2 ms budget they never used sank
// into it and stayed awake where the same world without a budget slept.
bool FrameScheduler::binding(const FrameSettings& settings) const {
  if (!m_reachedLately) return false;
  std::uint64_t units = 0;
  double micros = 0.0;
  // Pairs written already kept their contacts: they cost nothing.
  for (const DeferredPair& p : m_wholes) {
    if (p.written) continue;
    units += expectedCost(p.algorithm->lastWork(), kFirstWholeWork);
    micros += m_costs.expectedWholeMicros(*p.algorithm);
  }
  for (const DeferredPair& p : m_pairs) {
    if (p.written) continue;
    const std::uint64_t cost = expectedCost(p.meshMesh().needed(), kFirstGrant);
    units += cost;
    micros += static_cast<double>(cost) * m_costs.microsPerNodePair() + m_costs.writeMicros();
  }
  return units > settings.budgetNodePairs || micros > settings.budgetMicros;
}

// Every pair gets what it needed last step and a quarter more (at least kFirstGrant; a cut
// pair's need is twice what it used), at most an even share of what is left, so a tight
// budget still reaches every pair before any is refined. Pairs with a static (or
// kinematic) body go first and share the budget among themselves: a missed contact between
// two moving bodies lets them overlap for a step, a missed one with the world loses a body
// through the floor. Under a binding budget those whose bodies rest keep their contacts:
// before that (the world taking all it wanted), the mesh-mesh pairs of a pile on a box
// floor got 0.3 % of a quarter budget, wrote no contacts, and the pile sank through itself
// and the floor (docs/bullet-results.md).
void FrameScheduler::firstPass(const FrameSettings& settings) {
  // Before any query of this step: overdue() reads whether last step's query was cut.
  for (DeferredPair& pair : m_pairs) pair.overdue = overdue(pair);
  runMustRunWholes(settings);
  // Pairs written already (they kept their contacts: keepRestingContacts) wait for nothing.
  std::uint64_t anchoredPairs = 0, all = 0;
  for (const std::vector<DeferredPair>* pairs : {&m_pairs, &m_wholes}) {
    for (const DeferredPair& p : *pairs) {
      if (p.written) continue;
      anchoredPairs += anchored(p) ? 1 : 0;
      ++all;
    }
  }
  for (bool group : {true, false}) {
    std::uint64_t waiting = group ? anchoredPairs : all - anchoredPairs;
    // The whole pairs first (a box floor, a plane, a convex body: settled in one run), the
    // ones that moved most first. Those with a static body may take all that is left, the
    // others their share; a pair that does not fit is left for the refinement, and if it
    // does not run this step it keeps its last contacts.
    for (DeferredPair& pair : m_wholes) {
      if (pair.written || anchored(pair) != group) continue;
      if (pair.resting || rests(pair)) {  // resting: marked by runMustRunWholes
        pair.resting = true;
        --waiting;
        continue;
      }
      // A pair with the world goes before the mesh-mesh pairs' contact writing (a cut pair
      // that finds no time to write keeps its last contacts; a body that misses the floor
      // is lost).
      const double micros = microsLeft(settings, !group);
      const std::uint64_t among = group ? 1 : waiting;
      std::uint64_t units = nodePairsLeft(settings);
      if (units != kUnlimited) units /= among;
      runWhole(pair, units, std::isinf(micros) ? micros : micros / static_cast<double>(among),
               settings);
      --waiting;
    }
    firstQueries(group, waiting, settings);
  }
}

// Under a budget too small for every pair, a pair with the world whose mesh has barely moved
// since it last ran keeps its contacts (refreshed for the new poses): they are as good as new,
// and its cost goes to the pairs that changed.
bool FrameScheduler::rests(const DeferredPair& pair) const {
  return m_binding && anchored(pair) && pair.algorithm->barelyMoved(pair.motion);
}

// The whole pairs that run whatever the budget (arriving, losing their hold, approaching,
// sweeping), of either group, before any pair that may wait: run in their group's turn, the
// moving bodies' ones came after the pairs with the world had taken all that was left, and
// overran the budget by what they cost (BudgetAllPairs' mixed pile in double precision: p99
// 1.11x, two gears landing on each other taking 150 to 200 node pairs where 2 were left).
// What may wait then gets what they left.
void FrameScheduler::runMustRunWholes(const FrameSettings& settings) {
  for (DeferredPair& pair : m_wholes) {
    if (pair.written || pair.urgency > kMustRun) continue;
    if (rests(pair)) {
      pair.resting = true;
      continue;
    }
    runWhole(pair, nodePairsLeft(settings), microsLeft(settings, !anchored(pair)), settings);
  }
}

// The mesh-mesh queries of the first pass, in rounds of kRoundPairs pairs. A round's grants
// are decided before any of its queries runs: each pair what it wants, at most an even share
// of what is left once the grants before it in the round are spent (the serial rule, with
// the grants standing in for what their queries will use). The round's queries then run on
// the pool and are counted in pair order on this thread, and what they left unused goes to
// the next round. So a node-pair budget gives the same grants, contacts and trajectories at
// any thread count. Without a budget no grant depends on another query: one round.
void FrameScheduler::firstQueries(bool group, std::uint64_t waiting,
                                  const FrameSettings& settings) {
  // Overdue pairs (with the world) first: they run whatever the budget, and what they cost
  // is then known to the even shares of the others.
  std::uint64_t overduePairs = 0;
  for (const DeferredPair& pair : m_pairs) {
    overduePairs += !pair.written && anchored(pair) == group && pair.overdue ? 1 : 0;
  }
  if (overduePairs > 0) queryRounds(group, true, overduePairs, settings);
  queryRounds(group, false, waiting - overduePairs, settings);
}

void FrameScheduler::queryRounds(bool group, bool overdue, std::uint64_t waiting,
                                 const FrameSettings& settings) {
  const std::size_t roundPairs = unbudgeted(settings) ? m_pairs.size() : kRoundPairs;
  std::size_t next = 0;
  while (next < m_pairs.size()) {
    beginRound(settings);
    const double micros = microsLeft(settings);
    std::uint64_t reserved = 0;
    for (; next < m_pairs.size() && m_batch.size() < roundPairs; ++next) {
      const DeferredPair& pair = m_pairs[next];
      if (pair.written || anchored(pair) != group || pair.overdue != overdue) continue;
      const std::uint64_t wanted = firstWanted(pair);
      if (sweeps(pair) || overdue) {
        reserved = saturatingAdd(reserved, wanted);
        --waiting;
        m_batch.push_back(static_cast<std::uint32_t>(next));
        m_requests.push_back(QueryRequest::unbounded());
        continue;
      }
      const std::uint64_t grant = std::min(wanted, share(settings, waiting, reserved, micros));
      // A query cut by its grant or its time share is resumed by the refinement where it
      // stopped, and ends as it would have uncut. Only a budget reached lately makes a
      // starved pair descend otherwise (deepest overlaps first).
      const bool starved = grant < wanted && m_reachedLately;
      reserved = saturatingAdd(reserved, grant);
      m_batch.push_back(static_cast<std::uint32_t>(next));
      m_requests.push_back(QueryRequest::fresh(grant, timeShare(micros, waiting), starved));
      --waiting;
    }
    runRound(settings);
    for (std::size_t k = 0; k < m_batch.size(); ++k) {
      DeferredPair& pair = m_pairs[m_batch[k]];
      account(pair, m_requests[k]);
      settle(pair, settings);
    }
  }
}

void FrameScheduler::beginRound(const FrameSettings& settings) {
  m_batch.clear();
  m_requests.clear();
  const double micros = microsLeft(settings);
  m_roundDeadline = std::isinf(micros) ? micros : elapsedMicros() + micros;
}

// The round's traversals, each touching only its own pair and the immutable trees, so that
// they may run on any thread. A query's time cap is what is left of the round's deadline
// when it starts: the threads share the step's wall clock, not a sum of their times.
// A query that decided its pair also computes the pair's contact points (final: they are
// written in pair order after the round).
void FrameScheduler::runRound(const FrameSettings& settings) {
  auto job = [&](std::size_t k) {
    QueryRequest& request = m_requests[k];
    if (!request.whole && !std::isinf(m_roundDeadline)) {
      request.micros = std::clamp(m_roundDeadline - elapsedMicros(), 0.0, request.micros);
    }
    DeferredPair& pair = m_pairs[m_batch[k]];
    traverse(pair, request, settings);
    if (!isBudgetStop(pair.meshMesh().result().stop)) {
      pair.meshMesh().computeContacts(pair, settings);
    }
  };
  runOnPool(m_batch.size(), job);
}

// The contact points of the pairs the budget cut, on the pool; they are written in pair
// order by writeContacts.
void FrameScheduler::computeLateContacts(const FrameSettings& settings) {
  m_batch.clear();
  for (std::uint32_t i = 0; i < m_pairs.size(); ++i) {
    if (!m_pairs[i].written) m_batch.push_back(i);
  }
  auto job = [&](std::size_t k) {
    DeferredPair& pair = m_pairs[m_batch[k]];
    pair.meshMesh().computeContacts(pair, settings);
  };
  runOnPool(m_batch.size(), job);
}

template <class Job>
void FrameScheduler::runOnPool(std::size_t jobs, Job& job) {
  if (jobs == 0) return;
  m_pool.run(jobs, job);
  if (m_pool.threads() == 1) return;  // nothing ran in parallel
  m_stats.parallelMicros += m_pool.lastWallMicros();
  const auto& busy = m_pool.lastBusyMicros();
  for (std::size_t t = 0; t < busy.size() && t < m_stats.threadBusyMicros.size(); ++t) {
    m_stats.threadBusyMicros[t] += busy[t];
  }
}

// A pair with speculative contacts this step (a body that asked for CCD moves farther than
// its threshold) runs whole whatever the budget: skipped, or cut, it would miss the surface
// its body is about to pass (a gear at 50 m/s through a plane under a 1 us step, through a
// 4 cm mesh slab under 100 node pairs). So does a pair whose body has just landed
// (ManifoldAlgorithm::landing): cut under a 1 us step, a gear that had landed flat on the slab
// at 50 m/s sank 16 cm into it in the next steps; run whole, it comes to rest and keeps its
// contacts. Its cost overruns the budget for the steps the body is fast and half a second
// after (docs/bullet-budget.md, "Continuous collision detection").
// A pair with nothing to keep whose body has moved, and that was near last time (it cost
// more than its roots' test): a body arriving at the world. With the world it runs whatever is
// left (runWhole), so it goes first: run after the pairs that had contacts, it overran the
// budget by what it cost (BudgetAllPairs' mixed pile: p99 1.09x the budget, a gear landing on
// the plane taking 343 node pairs where 99 were left).
bool FrameScheduler::arriving(const DeferredPair& pair) const {
  const ManifoldAlgorithm& algorithm = *pair.algorithm;
  return !algorithm.holdsContacts() && algorithm.lastWork() > 1 &&
         !(pair.motion < algorithm.breakingThreshold()) && !supported(pair);
}

// A pair with the world that is losing its hold on its body: its kept contacts, re-measured
// at this step's poses, are deeper than the breaking threshold (the body is sinking into the
// world), or they hold the body up (holdsUp) and it has moved past the breaking threshold
// since the pair last ran (they no longer say where it rests). It runs whatever the budget,
// as an arriving pair does, and goes first with them: skipped while the walls beside a stack
// of gears on a plane took a 300 node-pair budget, a gear tipped over its one kept point and
// sank 0.17 into the plane; kept, sinking contacts let another sink 0.08 and jam under a
// wall's bottom face. Since the plane's contacts are sampled per region, a floor pair costs a
// resting gear tens of units, not a thousand.
bool FrameScheduler::losingHold(const DeferredPair& pair) {
  const ManifoldAlgorithm& algorithm = *pair.algorithm;
  if (!anchored(pair) || !algorithm.holdsContacts()) return false;
  const btScalar threshold = algorithm.breakingThreshold();
  if (algorithm.keptDepth() > threshold) return true;
  return !(pair.motion < threshold) && holdsUp(pair);
}

// A pair with the world whose body has moved past the breaking threshold since the pair last
// ran, and that was near then (it cost more than its roots' test) or never ran: the body may
// be reaching it. It runs whatever the budget, as a pair losing its hold does, even when
// another pair with the world holds the body up: at an eighth of the need the floor pairs of
// 30 rolling sliver pipes took the whole budget, a wall's pair with one of them never ran
// (new, and its pipe held up by the floor), and 9 pipes rolled through the walls. Under a
// binding budget these pairs sample 4 regions (runWhole): a first run of a pair still apart
// costs a few nodes.
bool FrameScheduler::approaching(const DeferredPair& pair) {
  const ManifoldAlgorithm& algorithm = *pair.algorithm;
  if (!anchored(pair) || pair.motion < algorithm.breakingThreshold()) return false;
  return algorithm.lastRun() == 0 || algorithm.lastWork() > 1;
}

std::uint8_t FrameScheduler::urgency(const DeferredPair& pair) const {
  if (arriving(pair)) return kArriving;
  return sweeps(pair) || losingHold(pair) || approaching(pair) ? kMustRun : kInTurn;
}

void FrameScheduler::noteSupported() {
  m_supported.clear();
  for (const std::vector<DeferredPair>* pairs : {&m_pairs, &m_wholes}) {
    for (const DeferredPair& p : *pairs) {
      // Held up, not merely touched: a body falling past a wall it brushed (one point)
      // counted as held, its pair with the box floor was skipped, and it fell through.
      if (!holdsUp(p)) continue;
      m_supported.push_back(p.object0->isStaticOrKinematicObject() ? p.object1 : p.object0);
    }
  }
  std::sort(m_supported.begin(), m_supported.end());
}

bool FrameScheduler::supported(const DeferredPair& pair) const {
  const btCollisionObject* body =
      pair.object0->isStaticOrKinematicObject() ? pair.object1 : pair.object0;
  return std::binary_search(m_supported.begin(), m_supported.end(), body);
}

bool FrameScheduler::sweeps(const DeferredPair& pair) {
  return pair.algorithm->speculativeReach() > 0 || pair.algorithm->landing();
}

// A mesh-mesh pair with the world cut step after step while its body closes in on the world:
// under a sixteenth of the need a landing gear's pair with a mesh bin was granted its even
// share (80 to 150 node pairs) and cut for 14 steps in a row, its few found and kept points
// 0.01 deep while the gear sank 0.03 a step, 0.45 into the floor, and others fell through
// (the bin lost 7 gears). Completed once, its contacts are true again and hold while it
// barely moves. Closing in, not moving: a body sliding along the world on its kept points
// (KeptContacts) is held by them.
bool FrameScheduler::overdue(const DeferredPair& pair) const {
  const ManifoldAlgorithm& algorithm = *pair.algorithm;
  // A pair never decided (cut since it began) has waited as long as it may.
  const std::uint64_t waitedSteps =
      algorithm.lastRun() == 0 ? kMaxSkippedSteps + 1 : m_step - algorithm.lastRun();
  if (!anchored(pair) || !pair.meshMesh().cut() || waitedSteps <= kMaxSkippedSteps) {
    return false;
  }
  // Bullet's normals on B point from body 1 to body 0: body 1 closes in along them.
  const btVector3 approach = approachInStep(pair, m_info->m_timeStep);
  const btVector3 normals = algorithm.lastNormalsOnB();
  const btScalar closing =
      normals.fuzzyZero() ? approach.length() : approach.dot(normals.normalized());
  // At this step's speed for as many steps as it waited: how far it closed in since its
  // contacts were made.
  return closing * static_cast<btScalar>(waitedSteps) > algorithm.breakingThreshold();
}

// What a mesh-mesh pair wants in the first pass: what it needed last step and a quarter more
// (a pair's need grows while bodies settle into each other), at least a few levels of both
// trees.
std::uint64_t FrameScheduler::firstWanted(const DeferredPair& pair) {
  return expectedCost(pair.meshMesh().needed(), kFirstGrant);
}

// A pair the first pass queried: a decided pair's contacts are final and written now (their
// time measured rather than estimated by the time the budget runs out); the others wait for
// the refinement.
void FrameScheduler::settle(DeferredPair& pair, const FrameSettings& settings) {
  --m_unqueried;
  if (pair.decided()) {
    writePair(pair, settings);
  } else {
    ++m_undecided;
  }
}

bool FrameScheduler::runWhole(DeferredPair& pair, std::uint64_t shareUnits, double microsShare,
                              const FrameSettings& settings) {
  ManifoldAlgorithm& algorithm = *pair.algorithm;
  // Its cost last time and a quarter more (bodies settling into each other touch more
  // triangles step by step; at least a few nodes for a pair never run), in work and in time
  // (a GJK pair costs far more per unit than a closed-form one).
  const std::uint64_t expected = expectedCost(algorithm.lastWork(), kFirstWholeWork);
  const double expectedMicros = m_costs.expectedWholeMicros(algorithm);
  if (expected > shareUnits || expectedMicros > microsShare) {
    // A pair expected to cost more than the whole budget would never run again (the
    // estimate is re-measured only by running), and its kept contacts would not hold a
    // moving body: it runs regardless, the step overrunning by that one pair, once its
    // bodies have moved as far as the contact breaking threshold (its kept contacts are no
    // longer where they touch: a box shoved along a grid sank through it, supported every
    // third step) or after kMaxSkippedSteps.
    const bool neverFits =
        expected > settings.budgetNodePairs || expectedMicros > settings.budgetMicros;
    const bool stale = m_step - algorithm.lastRun() > kMaxSkippedSteps ||
                       !(pair.motion < algorithm.breakingThreshold());
    // A pair with the world runs whatever the budget where skipping it could lose a body:
    // - `bare`, stale with no contact to keep (under a quarter of the need the box walls of
    //   a gear pile on a plane took the whole budget, and 37 of 50 gears fell through the
    //   plane); not while another pair with the world holds the body up (supported);
    // - losingHold: sinking into the world, or slipping where it holds the body up;
    // - approaching: its body moved past the breaking threshold and was near.
    // Running every pair with the world whose body moved overran the budget 1.3x while a
    // plane's contacts visited every vertex and boxes sampled 16 regions under any budget;
    // with both sampled, and 4 regions under a binding budget, BudgetAllPairs' mixed pile
    // keeps its p99 within 1.05x of the budget in both precisions (docs/bullet-results.md,
    // "Budgets that never take away a floor").
    const bool bare = anchored(pair) && !algorithm.holdsContacts() && !supported(pair);
    if (!(stale && (neverFits || bare)) && pair.urgency > kMustRun) return false;
  }
  // Under a budget too small for every pair, a box's or a plane's contacts are sampled from
  // fewer regions of the tree (kCoarseRegionLevel): the pairs with the world that run
  // whatever the budget (losingHold, arriving) overran it 1.12x at p99 in the
  // double-precision mixed pile of BudgetAllPairs with 16.
  // Set for this run only: a contactTest, or a step without a budget, samples 16.
  algorithm.setContactRegionLevel(m_binding ? kCoarseRegionLevel : kContactRegionLevel);
  PairWrappers wrappers(pair);
  btManifoldResult result(&wrappers.body0, &wrappers.body1);
  const Clock::time_point start = Clock::now();
  std::uint64_t work = 0;
  double gatheredMicros = 0.0;
  if (pair.gathered >= 0) {  // gathered on the pool: only the writing is left
    GatheredContacts& gathered = m_gathered[static_cast<std::size_t>(pair.gathered)];
    work = gathered.work;
    gatheredMicros = gathered.micros;
    algorithm.writeGathered(&wrappers.body0, &wrappers.body1, &result, gathered.selection, work,
                            m_step);
  } else {
    work = algorithm.collideScheduled(&wrappers.body0, &wrappers.body1, *m_info, &result, m_step);
  }
  const double micros =
      gatheredMicros + std::chrono::duration<double, std::micro>(Clock::now() - start).count();
  algorithm.setContactRegionLevel(kContactRegionLevel);
  algorithm.setLastMicros(micros);
  m_costs.measureWhole(work, micros);
  m_stats.nodePairs += work;
  m_stats.otherNodePairs += work;
  pair.written = true;
  return true;
}

void FrameScheduler::gatherWholes(const FrameSettings& settings) {
  m_gathering.clear();
  for (DeferredPair& pair : m_wholes) pair.gathered = -1;
  // Under any budget a whole pair may not run at all, and on one thread nothing is gained.
  if (m_pool.threads() == 1 || !unbudgeted(settings)) return;
  for (DeferredPair& pair : m_wholes) {
    if (pair.written) continue;  // it kept its contacts
    PairWrappers wrappers(pair);
    if (!pair.algorithm->gathersOffThread(&wrappers.body0, &wrappers.body1)) continue;
    pair.algorithm->prepareGather(&wrappers.body0, &wrappers.body1);  // Bullet's state: here
    pair.gathered = static_cast<std::int32_t>(m_gathering.size());
    m_gathering.push_back(&pair);
  }
  if (m_gathered.size() < m_gathering.size()) m_gathered.resize(m_gathering.size());
  auto job = [this](std::size_t i) {
    const DeferredPair& pair = *m_gathering[i];
    GatheredContacts& out = m_gathered[i];
    PairWrappers wrappers(pair);
    const Clock::time_point start = Clock::now();
    // Through the btManifoldResult runWhole makes, whose closest-point threshold is 0.
    out.work = pair.algorithm->gather(&wrappers.body0, &wrappers.body1, 0, out.selection);
    out.micros = std::chrono::duration<double, std::micro>(Clock::now() - start).count();
  };
  runOnPool(m_gathering.size(), job);
}

void FrameScheduler::keepSkipped() {
  for (DeferredPair& pair : m_wholes) {
    m_stats.neededNodePairs += pair.algorithm->lastWork();
    m_stats.fromScratchNodePairs += pair.algorithm->lastWork();
    if (pair.written) continue;
    PairWrappers wrappers(pair);
    pair.algorithm->keepLastContacts(&wrappers.body0, &wrappers.body1);
    ++m_stats.otherKeptPairs;
  }
}

// Pairs whose bodies barely moved against each other since their contacts were made keep
// them, re-measured at the new poses, and cost nothing this step (Jolt, PhysX and Box2D
// recycle contacts the same way): a resting pile pays only for what moves, and its contacts
// hold still, so that Bullet's solver settles it and lets it sleep. A mesh-mesh pair a
// budget cut is not kept: its contacts were not all made. Decided before the budget is
// spent, from the poses alone, so that node-pair budgets stay reproducible and a budget
// never reached changes nothing.
// Until the first pass, a pair is written only if it kept its contacts here.
void FrameScheduler::keepRestingContacts() {
  const auto keep = [](DeferredPair& pair) {
    const PairWrappers wrappers(pair);
    pair.algorithm->keepLastContacts(&wrappers.body0, &wrappers.body1);
    pair.written = true;
  };
  for (DeferredPair& pair : m_pairs) {
    MeshMeshAlgorithm& algorithm = pair.meshMesh();
    if (algorithm.cut() || !algorithm.contactsStillHold(algorithm.motionSinceLastRun(
                               pair.transform0, pair.transform1))) {
      continue;
    }
    keep(pair);
    pair.confidence = 1.0;
    pair.completeness = 1.0;
    --m_unqueried;
    ++m_stats.reusedPairs;
  }
  for (DeferredPair& pair : m_wholes) {
    if (!pair.algorithm->contactsStillHold(pair.motion)) continue;
    keep(pair);
    ++m_stats.otherReusedPairs;
  }
}

// While budget is left, the least complete pair gets as much again as it had: resumed depth
// first, re-run best first (ties: pairs with a static body, then the earlier pair, so that
// node-pair budgets stay reproducible).
void FrameScheduler::refine(const FrameSettings& settings) {
  // Whole pairs that did not fit their share: in turn, while what is left covers them; those
  // that rest only once the mesh-mesh pairs are refined (their kept contacts are as good as
  // new: what the first pass left goes to the pairs that changed).
  runWholesLeft(settings, false);
  m_order.clear();
  for (std::uint32_t i = 0; i < m_pairs.size(); ++i) {
    if (!m_pairs[i].decided()) m_order.push_back(i);
  }
  // Least complete first; among equally complete pairs those with a static body (the ones
  // that lose bodies through the floor), then the earlier.
  const auto moreCertain = [this](std::uint32_t x, std::uint32_t y) {
    const double cx = m_pairs[x].completeness, cy = m_pairs[y].completeness;
    if (cx != cy) return cx > cy;
    const bool ax = anchored(m_pairs[x]), ay = anchored(m_pairs[y]);
    return ax != ay ? ay : x > y;
  };
  std::make_heap(m_order.begin(), m_order.end(), moreCertain);
  // In rounds: the kRoundPairs least complete pairs, their grants decided in that order
  // before any of them runs, queried on the pool, counted in that order.
  while (!m_order.empty()) {
    beginRound(settings);
    m_deferred.clear();
    const double micros = microsLeft(settings);
    std::uint64_t reserved = 0;
    while (!m_order.empty() && m_batch.size() < kRoundPairs) {
      std::pop_heap(m_order.begin(), m_order.end(), moreCertain);
      const std::uint32_t index = m_order.back();
      m_order.pop_back();
      const DeferredPair& pair = m_pairs[index];
      const std::uint64_t left = share(settings, 1, reserved, micros);
      // As much again as it had (doubling its total), at least kMinGrowth more.
      const std::uint64_t more = std::max(pair.grant, kMinGrowth);
      QueryRequest request;
      if (!bestFirst(settings)) {
        // The depth-first traversal resumes where it stopped: nothing is redone.
        // A grant smaller than one expansion could only be used by overshooting the step.
        const std::uint64_t grant = std::min(more, left);
        if (grant < kNodePairsPerExpansion || !(micros > 0.0)) {
          deferOrDrop(index, reserved);
          continue;
        }
        request = QueryRequest::resumed(grant, micros);
      } else {
        // The best-first one starts again with the larger grant.
        const std::uint64_t grant = std::min(pair.grant + more, left);
        if (grant <= pair.grant || !(micros > 0.0)) {
          deferOrDrop(index, reserved);
          continue;
        }
        request = QueryRequest::fresh(grant, micros);
      }
      reserved = saturatingAdd(reserved, request.grant);
      m_batch.push_back(index);
      m_requests.push_back(request);
    }
    runRound(settings);
    for (std::size_t k = 0; k < m_batch.size(); ++k) {
      DeferredPair& pair = m_pairs[m_batch[k]];
      const std::uint64_t progress = account(pair, m_requests[k]);
      if (pair.decided()) {
        --m_undecided;
        writePair(pair, settings);
      } else if (progress > 0) {  // one that could not take a step would be re-run forever
        m_order.push_back(m_batch[k]);
        std::push_heap(m_order.begin(), m_order.end(), moreCertain);
      }
    }
    // What the round's queries left unused is for the pairs it had no room for.
    for (std::uint32_t index : m_deferred) {
      m_order.push_back(index);
      std::push_heap(m_order.begin(), m_order.end(), moreCertain);
    }
  }
  runWholesLeft(settings, true);
}

// A pair the round has no grant for: while the round's earlier grants hold budget they may
// not use, it waits for the next round; with nothing reserved, nothing is left for it. Dropped
// at once, pairs behind a round's reservations were cut with a tenth of a node-pair budget
// unspent (FrameBudget.ANodePairBudgetJustAboveTheNeedChangesNothing).
void FrameScheduler::deferOrDrop(std::uint32_t index, std::uint64_t reserved) {
  if (reserved > 0) m_deferred.push_back(index);
}

void FrameScheduler::runWholesLeft(const FrameSettings& settings, bool resting) {
  for (DeferredPair& pair : m_wholes) {
    if (!pair.written && (resting || !pair.resting)) {
      runWhole(pair, nodePairsLeft(settings), microsLeft(settings, !anchored(pair)), settings);
    }
  }
}

// Whether a time budget has no room left for one more cut pair's contacts.
bool FrameScheduler::outOfTime(const FrameSettings& s) const {
  if (std::isinf(s.budgetMicros)) return false;
  return elapsedMicros() + m_costs.lateWriteMicros() > s.budgetMicros;
}

// Writes a pair's contacts and measures the time it took.
double FrameScheduler::writePair(DeferredPair& pair, const FrameSettings& settings) {
  const Clock::time_point start = Clock::now();
  const ContactCount c = pair.meshMesh().writeContacts(pair, settings);
  if (pair.decided()) {
    const PairWrappers wrappers(pair);
    pair.algorithm->noteContactsMade(&wrappers.body0, &wrappers.body1, m_step);
  }
  m_stats.exactContacts += c.exact;
  m_stats.plausibleContacts += c.plausible;
  pair.written = true;
  const double micros = std::chrono::duration<double, std::micro>(Clock::now() - start).count();
  m_stats.contactMicros += micros;
  return micros;
}

void FrameScheduler::meshPairs(std::vector<MeshPairReport>& out) const {
  out.clear();
  for (const DeferredPair& pair : m_pairs) out.push_back(reportOf(pair));
}

// The pairs still unwritten (those the budget cut), then the step's statistics.
void FrameScheduler::writeContacts(const FrameSettings& settings) {
  // A time budget with no room left for one cut pair's contacts computes none of them.
  if (!outOfTime(settings)) computeLateContacts(settings);
  const double early = m_stats.contactMicros;
  std::uint32_t late = 0;
  MeshPairTally tally;
  for (DeferredPair& pair : m_pairs) {
    if (!pair.written) {
      if (outOfTime(settings)) {
        // Writing a cut pair's contacts would overrun the step: it keeps last step's.
        PairWrappers wrappers(pair);
        pair.algorithm->keepLastContacts(&wrappers.body0, &wrappers.body1);
        ++m_stats.lateKeptPairs;
      } else {
        writePair(pair, settings);
        ++late;
      }
    }
    tally.add(pair, m_stats);
  }
  tally.finish(m_pairs.size(), m_stats);
  const std::uint32_t earlyPairs = static_cast<std::uint32_t>(m_pairs.size()) - late;
  m_costs.measureWrites(early, earlyPairs, m_stats.contactMicros - early, late);
}

}  // namespace adb::detail
