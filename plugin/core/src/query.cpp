// The collision query: the paper's probability-guided traversal (Fig. 3) and the exact mode.
//
//   traverse(A, B):                                  # ADB mode, paper Fig. 3 plus budgets
//     q = max-heap by probability; k = 0; q.insert(rootA, rootB, 1)
//     while q not empty and budget left:
//       (A, B) = q.pop()
//       if A and B are leaves: test their triangles exactly; a hit is certain -> collision
//       for all children A[i], B[j] (a leaf is its own only child):
//         p = computeProb(A[i], B[j])                # pair_probability.cpp
//         if p > p_min and not both leaves: k += 1, keep as witness
//                                          if k >= k_min: return collision
//         if p > 0: q.insert(A[i], B[j], p)
//     return the better-supported answer (see confidence below)
//
// Leaf pairs are never accepted on probability: the tree keeps triangles, so they are decided
// exactly when popped. Confidence (docs/probability-model.md): for "collision", the largest p
// of the accepted pairs (1 after an exact hit): the model's probability that one of them
// really intersects, with no independence assumed between nested pairs. For "no collision",
// 1 - min(1, U), with U the sum of Pr[X >= 1] over the queued pairs plus E[X] over the pairs
// pruned so far: it bounds the chance that any unresolved pair collides. Each frontier is a
// cover of all unresolved pairs, so the smallest U seen so far stays valid: both confidences
// only grow with budget.
//
// Exact mode is a depth-first descent over overlapping boxes. Cut by a budget, its stack is
// estimated by the same model (openPairs(), and the confidence 1 - min(1, U)) and can be
// resumed later. Contact generation samples hits per contact region (hitsPerRegion): once a
// region holds its quota, its remaining pairs are skipped at no cost, in either mode.
#include "adb/core/query.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>

#include "adb/core/triangle_test.h"
#include "pair_probability.h"

namespace adb {

struct QueryScratchAccess {
  using Entry = OpenPair;
  static std::vector<Entry>& heap(QueryScratch& s) { return s.m_heap; }
  static std::vector<Witness>& witnesses(QueryScratch& s) { return s.m_witnesses; }
  static std::vector<std::uint32_t>& regionHits(QueryScratch& s) { return s.m_regionHits; }
  // Whether `s` holds an exact query of trees a and b that a budget stopped. The node
  // counts guard the stack's indices should another tree have taken a freed one's address.
  static bool resumable(const QueryScratch& s, const AdbTree& a, const AdbTree& b) {
    return s.m_resumeA == &a && s.m_resumeB == &b && s.m_resumeNodesA == a.nodes().size() &&
           s.m_resumeNodesB == b.nodes().size();
  }
  static bool& resumeHit(QueryScratch& s) { return s.m_resumeHit; }
  static void markResumable(QueryScratch& s, const AdbTree* a, const AdbTree* b) {
    s.m_resumeA = a;
    s.m_resumeB = b;
    s.m_resumeNodesA = a ? a->nodes().size() : 0;
    s.m_resumeNodesB = b ? b->nodes().size() : 0;
  }
};

namespace {

using Clock = std::chrono::steady_clock;
using Entry = QueryScratchAccess::Entry;
constexpr std::uint32_t kNoRegion = OpenPair::kNoRegion;

// The clock is read once this much work has been done since the last read, counting 4 per
// popped pair (its evaluations, ~0.1 us each) and 1 per triangle test: a short query is not
// dominated by clock reads, and a budget overshoots by a few microseconds at most (plus one
// leaf pair: at most 15 x 15 triangle tests, which are never interrupted).
constexpr unsigned kClockInterval = 64;

bool heapLess(const Entry& x, const Entry& y) { return x.p < y.p; }

// The doubt an unresolved pair carries: Pr[X >= 1], or where rounding left one side no
// possible collision cell (so Pr[X >= 1] = 0 for boxes that do overlap), E[X] before
// rounding, as for a pruned pair (Markov).
double doubtOf(const detail::PairEstimate& est) {
  return est.upper > 0.0 ? est.upper : est.expected;
}

// Whether boxes [loX, hiX] and [loY, hiY] are separated along some axis by more than `gap`.
bool boxesApart(const Vec3& loX, const Vec3& hiX, const Vec3& loY, const Vec3& hiY, double gap) {
  return (loX.array() > hiY.array() + gap).any() || (loY.array() > hiX.array() + gap).any();
}

class Traversal {
 public:
  Traversal(const AdbTree& a, const Pose& poseA, const AdbTree& b, const Pose& poseB,
            const QuerySettings& settings, QueryScratch& scratch)
      : m_a{&a, a.maxDepth()},
        m_b{&b, b.maxDepth()},
        m_frame(detail::RelativeFrame::between(a, poseA, b, poseB)),
        m_settings(settings),
        m_heap(QueryScratchAccess::heap(scratch)),
        m_witnesses(QueryScratchAccess::witnesses(scratch)),
        m_regionHits(QueryScratchAccess::regionHits(scratch)),
        m_scratch(scratch),
        m_start(Clock::now()),
        m_timed(std::isfinite(settings.budgetMicros)),
        m_budgeted(m_timed ||
                   settings.budgetNodePairs != std::numeric_limits<std::uint64_t>::max()),
        m_resuming(settings.resume && settings.mode == QueryMode::Exact &&
                   QueryScratchAccess::resumable(scratch, a, b)) {
    if (!m_resuming) {
      m_heap.clear();
      m_witnesses.clear();
      m_regionHits.clear();
      QueryScratchAccess::resumeHit(scratch) = false;
    }
    QueryScratchAccess::markResumable(scratch, nullptr, nullptr);
  }

  QueryResult run() {
    if (m_settings.mode == QueryMode::Exact) {
      runExact();
      if (m_result.stop == StopReason::TimeBudget || m_result.stop == StopReason::WorkBudget) {
        QueryScratchAccess::markResumable(m_scratch, m_a.tree, m_b.tree);
      }
    } else {
      runAdb();
    }
    m_result.witnessCount = static_cast<std::uint32_t>(m_witnesses.size());
    m_result.seconds = std::chrono::duration<double>(Clock::now() - m_start).count();
    return m_result;
  }

 private:
  // --- budgets -------------------------------------------------------------------------
  // Checked before a pair is expanded (up to 4 evaluations), so a pair is never
  // half-expanded and nodePairs never exceeds max(1, budgetNodePairs): the roots' own test
  // is always made.
  bool budgetLeft() {
    if (m_result.nodePairs + 4 > m_settings.budgetNodePairs) {
      m_result.stop = StopReason::WorkBudget;
      return false;
    }
    if (!m_timed) return true;
    m_workSinceClock += 4;
    if (m_workSinceClock >= kClockInterval || m_firstCheck) {
      m_workSinceClock = 0;
      m_firstCheck = false;
      const double us = std::chrono::duration<double, std::micro>(Clock::now() - m_start).count();
      if (us >= m_settings.budgetMicros) {
        m_result.stop = StopReason::TimeBudget;
        return false;
      }
    }
    return true;
  }

  // --- witnesses -----------------------------------------------------------------------
  void addWitness(const Witness& w) {
    if (m_witnesses.size() < m_settings.maxWitnesses) {
      m_witnesses.push_back(w);
    } else {
      ++m_result.witnessesDropped;
    }
  }

  // --- contact regions (QuerySettings::hitsPerRegion) -------------------------------------
  // The region of a child pair at depths (da, db): its parent's, or a new one where the pair
  // is the first on its path to reach regionDepth.
  std::uint32_t childRegion(std::uint32_t parent, int da, int db) {
    if (parent != kNoRegion) return parent;
    if (m_settings.hitsPerRegion == 0 || da + db < m_settings.regionDepth) return kNoRegion;
    m_regionHits.push_back(0);
    return static_cast<std::uint32_t>(m_regionHits.size() - 1);
  }

  // A region with its hits found: the rest of it is skipped.
  bool regionFull(std::uint32_t region) const {
    return region != kNoRegion && m_regionHits[region] >= m_settings.hitsPerRegion;
  }

  // Tests the triangle pairs of two leaves (all, or until their region is full); records
  // hits. Returns true on a hit.
  bool testLeaves(std::uint32_t ia, std::uint32_t ib, std::uint32_t region) {
    const Node& na = m_a.tree->nodes()[ia];
    const Node& nb = m_b.tree->nodes()[ib];
    const auto& va = m_a.tree->localVertices();
    const auto& vb = m_b.tree->localVertices();
    const auto& ta = m_a.tree->triangles();
    const auto& tb = m_b.tree->triangles();
    // B's triangles mapped into A's frame once per leaf pair (at most 15 x 3 points), and
    // the boxes of both leaves' triangles in that frame (Eigen leaves them uninitialised:
    // nothing is written for the slots a leaf does not use).
    Vec3 mapped[15][3];
    Vec3 loA[15], hiA[15], loB[15], hiB[15];
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    for (std::uint32_t j = 0; j < nb.triangleCount(); ++j) {
      for (int k = 0; k < 3; ++k) {
        mapped[j][k] = m_frame.bToA(vb[tb[nb.firstTriangle() + j][k]]);
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
    // thousand times trianglesIntersect's tolerance (1e-12 of the pair's extent), so the
    // answer is the one the test would give. Most pairs of two overlapping leaves are apart.
    const double gap = 1e-9 * (hi - lo).maxCoeff();
    bool hit = false;
    for (std::uint32_t i = 0; i < na.triangleCount(); ++i) {
      const Triangle& t = ta[na.firstTriangle() + i];
      for (std::uint32_t j = 0; j < nb.triangleCount(); ++j) {
        if (boxesApart(loA[i], hiA[i], loB[j], hiB[j], gap)) continue;
        ++m_result.triangleTests;
        ++m_workSinceClock;
        if (!trianglesIntersect(va[t[0]], va[t[1]], va[t[2]], mapped[j][0], mapped[j][1],
                                mapped[j][2])) {
          continue;
        }
        hit = true;
        Witness w;
        w.nodeA = ia;
        w.nodeB = ib;
        w.triangleA = na.firstTriangle() + i;
        w.triangleB = nb.firstTriangle() + j;
        w.probability = 1.0f;
        addWitness(w);
        if (m_settings.stopAtFirstHit) return true;
        if (region != kNoRegion && ++m_regionHits[region] >= m_settings.hitsPerRegion) {
          return true;
        }
      }
    }
    return hit;
  }

  // The children of a node for the simultaneous descent: a leaf is its own only child.
  static int children(const Node& n, std::uint32_t self, std::uint32_t out[2]) {
    if (n.isLeaf()) {
      out[0] = self;
      return 1;
    }
    out[0] = n.firstChild();
    out[1] = n.firstChild() + 1;
    return 2;
  }

  // --- exact mode: depth-first over overlapping boxes ----------------------------------
  void runExact() {
    if (!m_resuming) {
      ++m_result.nodePairs;
      if (!detail::nodesOverlap(m_a, 0, m_b, 0, m_frame)) {
        finish(false, 1.0, StopReason::Completed);
        return;
      }
      m_heap.push_back(Entry{1.0f, 1.0f, 0, 0, childRegion(kNoRegion, 0, 0), 0, 0});
    }
    bool& hit = QueryScratchAccess::resumeHit(m_scratch);
    while (!m_heap.empty()) {
      if (regionFull(m_heap.back().region)) {  // skipping costs no budget
        m_heap.pop_back();
        continue;
      }
      if (!budgetLeft()) {
        // The stack is what is left unexplored: estimated by the model, it gives the cut
        // query its confidence and the caller its plausible contacts (openPairs()).
        const double doubt = estimateFrontier();
        finish(hit, hit ? 1.0 : 1.0 - std::min(1.0, doubt), m_result.stop);
        return;
      }
      const Entry e = m_heap.back();
      m_heap.pop_back();
      const Node& na = m_a.tree->nodes()[e.a];
      const Node& nb = m_b.tree->nodes()[e.b];
      if (na.isLeaf() && nb.isLeaf()) {
        if (testLeaves(e.a, e.b, e.region)) {
          hit = true;
          if (m_settings.stopAtFirstHit) {
            m_heap.clear();  // decided: nothing is left open
            finish(true, 1.0, StopReason::ExactHit);
            return;
          }
        }
        continue;
      }
      std::uint32_t ca[2], cb[2];
      const int na2 = children(na, e.a, ca), nb2 = children(nb, e.b, cb);
      const int da = na.isLeaf() ? e.depthA : e.depthA + 1;
      const int db = nb.isLeaf() ? e.depthB : e.depthB + 1;
      // Under a budget the overlapping children go on the stack shallowest first, so that
      // the deepest overlap is explored first: a budget that cuts the descent has then seen
      // the deepest contacts, the ones that keep bodies apart. A descent that cannot be cut
      // keeps the trees' order, which samples the same triangle pairs step after step
      // (deepest first, near-equal depths swap with every small motion, and the contacts of
      // a resting stack jumped: its top boxes drifted up to 40 % further).
      Entry kids[4];
      float depth[4];
      int count = 0;
      for (int i = 0; i < na2; ++i) {
        for (int j = 0; j < nb2; ++j) {
          ++m_result.nodePairs;
          const double d = m_budgeted ? detail::overlapDepth(m_a, ca[i], m_b, cb[j], m_frame)
                                      : (detail::nodesOverlap(m_a, ca[i], m_b, cb[j], m_frame)
                                             ? 0.0
                                             : -1.0);
          if (d < 0.0) continue;
          int k = count++;
          for (; k > 0 && depth[k - 1] > static_cast<float>(d); --k) {
            kids[k] = kids[k - 1];
            depth[k] = depth[k - 1];
          }
          kids[k] = Entry{1.0f, 1.0f, ca[i], cb[j], kNoRegion, static_cast<std::uint16_t>(da),
                          static_cast<std::uint16_t>(db)};
          depth[k] = static_cast<float>(d);
        }
      }
      for (int k = 0; k < count; ++k) {
        kids[k].region = childRegion(e.region, da, db);
        m_heap.push_back(kids[k]);
      }
    }
    finish(hit, 1.0, StopReason::Completed);
  }

  // --- ADB mode: the paper's priority traversal ----------------------------------------
  void push(const detail::PairEstimate& est, std::uint32_t a, std::uint32_t b,
            std::uint32_t region, int da, int db) {
    const Entry e{static_cast<float>(est.lower), static_cast<float>(doubtOf(est)), a, b, region,
                  static_cast<std::uint16_t>(da), static_cast<std::uint16_t>(db)};
    m_heap.push_back(e);
    std::push_heap(m_heap.begin(), m_heap.end(), heapLess);
    m_upperSum += e.upper;  // the stored float, the same value the pop subtracts
  }

  void runAdb() {
    ++m_result.nodePairs;
    const detail::PairEstimate root = detail::estimatePair(m_a, 0, 0, m_b, 0, 0, m_frame);
    if (!root.overlap) {
      finish(false, 1.0, StopReason::Completed);
      return;
    }
    // The paper inserts the roots with probability 1: LB is 0 at depth 0, so Eq. 3 is 0.
    m_heap.push_back(
        Entry{1.0f, static_cast<float>(root.upper), 0, 0, childRegion(kNoRegion, 0, 0), 0, 0});
    m_upperSum = static_cast<float>(root.upper);
    m_minUpperSum = m_upperSum;
    while (!m_heap.empty()) {
      if (!budgetLeft()) {
        finishUncertain(m_result.stop);
        return;
      }
      std::pop_heap(m_heap.begin(), m_heap.end(), heapLess);
      const Entry e = m_heap.back();
      m_heap.pop_back();
      m_upperSum -= e.upper;
      if (!regionFull(e.region) && expandAdb(e)) return;
      // Rounding must not make an empty queue look doubtful, nor a sum negative.
      m_upperSum = m_heap.empty() ? 0.0 : std::max(0.0, m_upperSum);
      m_minUpperSum = std::min(m_minUpperSum, m_upperSum + m_prunedMass);
    }
    finishUncertain(StopReason::Completed);
  }

  // Expands one popped pair. Returns true when the query is decided.
  bool expandAdb(const Entry& e) {
    const Node& na = m_a.tree->nodes()[e.a];
    const Node& nb = m_b.tree->nodes()[e.b];
    if (na.isLeaf() && nb.isLeaf()) {
      if (testLeaves(e.a, e.b, e.region)) {
        m_exactHit = true;
        if (m_settings.stopAtFirstHit) {
          dropFullRegions();
          std::make_heap(m_heap.begin(), m_heap.end(), heapLess);
          finish(true, 1.0, StopReason::ExactHit);
          return true;
        }
      }
      return false;
    }
    std::uint32_t ca[2], cb[2];
    const int na2 = children(na, e.a, ca), nb2 = children(nb, e.b, cb);
    const int da = na.isLeaf() ? e.depthA : e.depthA + 1;
    const int db = nb.isLeaf() ? e.depthB : e.depthB + 1;
    for (int i = 0; i < na2; ++i) {
      for (int j = 0; j < nb2; ++j) {
        ++m_result.nodePairs;
        const detail::PairEstimate est = detail::estimatePair(m_a, ca[i], da, m_b, cb[j], db,
                                                              m_frame);
        if (!est.overlap) continue;
        if (!(est.lower > 0.0) && m_settings.pruneImprobable) {  // paper: only p > 0
          m_prunedMass += est.expected;
          continue;
        }
        const bool leaves = m_a.tree->nodes()[ca[i]].isLeaf() && m_b.tree->nodes()[cb[j]].isLeaf();
        if (!leaves && est.lower > m_settings.pMin) {
          ++m_result.collisionPairs;
          m_bestAccepted = std::max(m_bestAccepted, est.lower);
          if (m_settings.nodeWitnesses) {
            Witness w;
            w.nodeA = ca[i];
            w.nodeB = cb[j];
            w.probability = static_cast<float>(est.lower);
            addWitness(w);
          }
          if (m_result.collisionPairs >= static_cast<std::uint32_t>(m_settings.kMin)) {
            dropFullRegions();
            std::make_heap(m_heap.begin(), m_heap.end(), heapLess);
            finish(true, m_exactHit ? 1.0 : m_bestAccepted, StopReason::QualityReached);
            return true;
          }
        }
        push(est, ca[i], cb[j], childRegion(e.region, da, db), da, db);
      }
    }
    return false;
  }

  // The answer when neither k_min nor an exact hit decided. The paper answers "no collision"
  // when the queue runs out; a budget stop answers the same, with the doubt left in the
  // queue (and in what was pruned) as its confidence, so a cut query says "no, but unsure".
  // Accepted pairs below k_min are evidence the paper does not act on: they are not
  // witnesses of a "no".
  void finishUncertain(StopReason why) {
    dropFullRegions();
    std::make_heap(m_heap.begin(), m_heap.end(), heapLess);
    if (m_exactHit) {
      finish(true, 1.0, why);
      return;
    }
    m_witnesses.clear();
    m_result.witnessesDropped = 0;
    finish(false, 1.0 - std::min(1.0, m_minUpperSum), why);
  }

  // Pairs of regions whose hits were found are resolved, not open: a cut query leaves only
  // the others in openPairs(). The order of the rest is kept (exact mode resumes from it).
  void dropFullRegions() {
    if (m_regionHits.empty()) return;
    const auto full = [this](const Entry& e) { return regionFull(e.region); };
    m_heap.erase(std::remove_if(m_heap.begin(), m_heap.end(), full), m_heap.end());
  }

  // Exact mode cut by a budget: the model's estimates for the pairs left on the stack (at
  // most 3 per level of depth, not counted as node pairs). Returns their doubt: the sum of
  // Pr[X >= 1].
  double estimateFrontier() {
    dropFullRegions();
    double doubt = 0.0;
    for (Entry& e : m_heap) {
      const detail::PairEstimate est =
          detail::estimatePair(m_a, e.a, e.depthA, m_b, e.b, e.depthB, m_frame);
      e.p = static_cast<float>(est.lower);
      e.upper = static_cast<float>(doubtOf(est));
      doubt += e.upper;
    }
    return doubt;
  }

  void finish(bool collides, double confidence, StopReason why) {
    m_result.collides = collides;
    m_result.confidence = std::clamp(confidence, 0.0, 1.0);
    m_result.stop = why;
  }

  detail::TreeConstants m_a, m_b;
  detail::RelativeFrame m_frame;
  const QuerySettings& m_settings;
  std::vector<Entry>& m_heap;
  std::vector<Witness>& m_witnesses;
  std::vector<std::uint32_t>& m_regionHits;
  QueryScratch& m_scratch;
  Clock::time_point m_start;
  bool m_timed;
  bool m_budgeted;  // a budget may cut the query
  bool m_resuming;
  unsigned m_workSinceClock = 0;
  bool m_firstCheck = true;  // the first check reads the clock: a zero budget stops at once
  QueryResult m_result;
  double m_upperSum = 0.0;
  double m_minUpperSum = 0.0;
  double m_bestAccepted = 0.0;  // largest p of the accepted pairs
  double m_prunedMass = 0.0;    // sum of E[X] over the pairs pruned for p = 0
  bool m_exactHit = false;
};

}  // namespace

const char* toString(StopReason r) {
  switch (r) {
    case StopReason::Completed: return "completed";
    case StopReason::QualityReached: return "quality reached";
    case StopReason::ExactHit: return "exact hit";
    case StopReason::TimeBudget: return "time budget";
    case StopReason::WorkBudget: return "work budget";
  }
  return "unknown";
}

std::size_t QueryScratch::capacityBytes() const {
  return m_heap.capacity() * sizeof(Entry) + m_witnesses.capacity() * sizeof(Witness) +
         m_regionHits.capacity() * sizeof(std::uint32_t);
}

void validate(const QuerySettings& s) {
  if (!(s.pMin >= 0.0 && s.pMin <= 1.0)) {
    throw SettingsError("QuerySettings::pMin is " + std::to_string(s.pMin) +
                        "; it must be in [0, 1]");
  }
  if (s.kMin < 1) {
    throw SettingsError("QuerySettings::kMin is " + std::to_string(s.kMin) +
                        "; it must be at least 1");
  }
  if (s.regionDepth < 0) {
    throw SettingsError("QuerySettings::regionDepth is " + std::to_string(s.regionDepth) +
                        "; it must be >= 0");
  }
  if (std::isnan(s.budgetMicros) || s.budgetMicros < 0.0) {
    throw SettingsError("QuerySettings::budgetMicros is " + std::to_string(s.budgetMicros) +
                        "; it must be >= 0 (infinity for no budget)");
  }
}

namespace {

// The traversal inverts rotations by transposing them: a scaled or sheared "rotation" would
// silently misplace every box, so it is refused at the door.
constexpr double kOrthonormalTolerance = 1e-6;

void validatePose(const Pose& p, const char* which) {
  const auto fail = [&](const std::string& why) {
    throw PoseError(std::string("collide: pose ") + which + " " + why);
  };
  if (!p.rotation.allFinite() || !p.translation.allFinite()) fail("has a non-finite entry");
  const double off = (p.rotation.transpose() * p.rotation - Mat3::Identity()).cwiseAbs().maxCoeff();
  if (off > kOrthonormalTolerance) {
    fail("has a rotation that is not orthonormal (|R^T R - I| = " + std::to_string(off) + ")");
  }
}

}  // namespace

QueryResult collide(const AdbTree& a, const Pose& poseA, const AdbTree& b, const Pose& poseB,
                    const QuerySettings& settings, QueryScratch& scratch) {
  validate(settings);
  validatePose(poseA, "A");
  validatePose(poseB, "B");
  return Traversal(a, poseA, b, poseB, settings, scratch).run();
}

}  // namespace adb
