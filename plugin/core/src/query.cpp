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
#include "adb/core/query.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "adb/core/triangle_test.h"
#include "pair_probability.h"

namespace adb {

struct QueryScratchAccess {
  using Entry = OpenPair;
  static std::vector<Entry>& heap(QueryScratch& s) { return s.m_heap; }
  static std::vector<Witness>& witnesses(QueryScratch& s) { return s.m_witnesses; }
};

namespace {

using Clock = std::chrono::steady_clock;
using Entry = QueryScratchAccess::Entry;

// The clock is read once this much work has been done since the last read, counting 4 per
// popped pair (its evaluations, ~0.1 us each) and 1 per triangle test: a short query is not
// dominated by clock reads, and a budget overshoots by a few microseconds at most (plus one
// leaf pair: at most 15 x 15 triangle tests, which are never interrupted).
constexpr unsigned kClockInterval = 64;

bool heapLess(const Entry& x, const Entry& y) { return x.p < y.p; }

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
        m_start(Clock::now()),
        m_timed(std::isfinite(settings.budgetMicros)) {
    m_heap.clear();
    m_witnesses.clear();
  }

  QueryResult run() {
    if (m_settings.mode == QueryMode::Exact) {
      runExact();
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

  // Tests every triangle pair of two leaves; records hits. Returns true on a hit.
  bool testLeaves(std::uint32_t ia, std::uint32_t ib) {
    const Node& na = m_a.tree->nodes()[ia];
    const Node& nb = m_b.tree->nodes()[ib];
    const auto& va = m_a.tree->localVertices();
    const auto& vb = m_b.tree->localVertices();
    const auto& ta = m_a.tree->triangles();
    const auto& tb = m_b.tree->triangles();
    // B's triangles mapped into A's frame once per leaf pair (at most 15 x 3 points).
    Vec3 mapped[15][3];
    for (std::uint32_t j = 0; j < nb.triangleCount(); ++j) {
      for (int k = 0; k < 3; ++k) {
        mapped[j][k] = m_frame.bToA(vb[tb[nb.firstTriangle() + j][k]]);
      }
    }
    bool hit = false;
    for (std::uint32_t i = 0; i < na.triangleCount(); ++i) {
      const Triangle& t = ta[na.firstTriangle() + i];
      for (std::uint32_t j = 0; j < nb.triangleCount(); ++j) {
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
    ++m_result.nodePairs;
    if (!detail::nodesOverlap(m_a, 0, m_b, 0, m_frame)) {
      finish(false, 1.0, StopReason::Completed);
      return;
    }
    m_heap.push_back(Entry{1.0f, 1.0f, 0, 0, 0, 0});
    bool hit = false;
    while (!m_heap.empty()) {
      if (!budgetLeft()) {
        // Nothing is known about the pairs left unexplored: no model in exact mode. Its
        // stack is not a set of estimated pairs, so openPairs() reports none.
        m_heap.clear();
        finish(hit, hit ? 1.0 : 0.0, m_result.stop);
        return;
      }
      const Entry e = m_heap.back();
      m_heap.pop_back();
      const Node& na = m_a.tree->nodes()[e.a];
      const Node& nb = m_b.tree->nodes()[e.b];
      if (na.isLeaf() && nb.isLeaf()) {
        if (testLeaves(e.a, e.b)) {
          hit = true;
          if (m_settings.stopAtFirstHit) {
            finish(true, 1.0, StopReason::ExactHit);
            return;
          }
        }
        continue;
      }
      std::uint32_t ca[2], cb[2];
      const int na2 = children(na, e.a, ca), nb2 = children(nb, e.b, cb);
      for (int i = 0; i < na2; ++i) {
        for (int j = 0; j < nb2; ++j) {
          ++m_result.nodePairs;
          if (detail::nodesOverlap(m_a, ca[i], m_b, cb[j], m_frame)) {
            m_heap.push_back(Entry{1.0f, 1.0f, ca[i], cb[j], 0, 0});
          }
        }
      }
    }
    finish(hit, 1.0, StopReason::Completed);
  }

  // --- ADB mode: the paper's priority traversal ----------------------------------------
  void push(const detail::PairEstimate& est, std::uint32_t a, std::uint32_t b, int da, int db) {
    const Entry e{static_cast<float>(est.lower), static_cast<float>(est.upper), a, b,
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
    m_heap.push_back(Entry{1.0f, static_cast<float>(root.upper), 0, 0, 0, 0});
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
      if (expandAdb(e)) return;
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
      if (testLeaves(e.a, e.b)) {
        m_exactHit = true;
        if (m_settings.stopAtFirstHit) {
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
            finish(true, m_exactHit ? 1.0 : m_bestAccepted, StopReason::QualityReached);
            return true;
          }
        }
        push(est, ca[i], cb[j], da, db);
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
    if (m_exactHit) {
      finish(true, 1.0, why);
      return;
    }
    m_witnesses.clear();
    m_result.witnessesDropped = 0;
    finish(false, 1.0 - std::min(1.0, m_minUpperSum), why);
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
  Clock::time_point m_start;
  bool m_timed;
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
  return m_heap.capacity() * sizeof(Entry) + m_witnesses.capacity() * sizeof(Witness);
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
