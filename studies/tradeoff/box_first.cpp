// The box-first traversal (see box_first.h).
#include "box_first.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "adb/core/triangle_test.h"
#include "root_overlap.h"

namespace adb::tradeoff {
namespace {
using Clock = std::chrono::steady_clock;
}  // namespace

// Tree B's local frame seen from tree A's (for two copies of one model, both are its tree).
struct BoxFirstMethod::Frame {
  Mat3 rBA, absBA, rAB, absAB;
  Vec3 tBA, tAB;
  double slack = 0.0;  ///< absolute overlap tolerance for the rounding of the transform

  Vec3 bToA(const Vec3& x) const { return rBA * x + tBA; }
};

// The time budget of one query, checked by the core's rule (plugin/core/src/query.cpp) so
// that box-first and ADB overshoot a budget alike: the clock is read once kClockWork units
// of work have accumulated (a short query is not dominated by clock reads) and at the first
// check (a budget of 0 stops before any work). Triangle tests count: a leaf pair may run up
// to 15 x 15 of them, far more than one pair test.
struct BoxFirstMethod::Budget {
  Clock::time_point start = Clock::now();
  double micros;
  bool timed = std::isfinite(micros);
  bool firstCheck = true;
  std::uint32_t workSinceClock = 0;

  explicit Budget(double budgetUs) : micros(budgetUs) {}

  void countTriangleTest() { ++workSinceClock; }

  // Before a pair is popped: counts its work; true when the budget is spent.
  bool spent() {
    if (!timed) return false;
    workSinceClock += kWorkPerPair;
    if (workSinceClock < kClockWork && !firstCheck) return false;
    workSinceClock = 0;
    firstCheck = false;
    return std::chrono::duration<double, std::micro>(Clock::now() - start).count() >= micros;
  }
};

namespace {

// Rounding of the transform, relative to the scene's size (the core uses the same 1e-12):
// boxes that touch must not be separated by it.
constexpr double kRelativeSlack = 1e-12;

// Triangle pairs whose boxes are apart by more than this fraction of the leaf pair's extent
// are skipped untested: a thousand times trianglesIntersect's tolerance, so the test would
// have said "apart" too (the core's leaf test uses the same rule).
constexpr double kTriangleGap = 1e-9;

// A node's box, centre and half extents in its own tree-local frame, and the axis-aligned
// box of it in the other tree's frame.
struct MappedBox {
  Vec3 c, h;
  Vec3 cOther, hOther;
};

// `n`'s box mapped by x -> r x + t (absR = |r| maps half extents to the AABB's).
MappedBox mapBox(const Node& n, const Mat3& r, const Mat3& absR, const Vec3& t) {
  MappedBox m;
  m.c = 0.5 * (n.boxHi() + n.boxLo());
  m.h = 0.5 * (n.boxHi() - n.boxLo());
  m.cOther = r * m.c + t;
  m.hOther = absR * m.h;
  return m;
}

// Whether the intervals (centre c, half extent h) and (c2, h2) are apart on some axis.
bool apart(const Vec3& c, const Vec3& h, const Vec3& c2, const Vec3& h2, double slack) {
  return ((c2 - c).cwiseAbs().array() > (h + h2).array() + slack).any();
}

// The queue key of A's box `a` and B's box `b`: their overlap volume in A's frame, or -1
// when a face axis of either box separates them.
double overlapKey(const MappedBox& a, const MappedBox& b, double slack) {
  if (apart(a.c, a.h, b.cOther, b.hOther, slack)) return -1.0;
  if (apart(b.c, b.h, a.cOther, a.hOther, slack)) return -1.0;
  // Overlap volume in A's frame; >= 0 (touching boxes, within the slack, give 0).
  const Vec3 lo = (a.c - a.h).cwiseMax(b.cOther - b.hOther);
  const Vec3 hi = (a.c + a.h).cwiseMin(b.cOther + b.hOther);
  return (hi - lo).cwiseMax(Vec3::Zero()).prod();
}

int children(const Node& n, std::uint32_t self, std::uint32_t out[2]) {
  if (n.isLeaf()) {
    out[0] = self;  // a leaf is its own only child
    return 1;
  }
  out[0] = n.firstChild();
  out[1] = n.firstChild() + 1;
  return 2;
}

// Whether boxes [loX, hiX] and [loY, hiY] are separated along some axis by more than `gap`.
bool boxesApart(const Vec3& loX, const Vec3& hiX, const Vec3& loY, const Vec3& hiY, double gap) {
  return (loX.array() > hiY.array() + gap).any() || (loY.array() > hiX.array() + gap).any();
}

}  // namespace

BoxFirstMethod::BoxFirstMethod(std::shared_ptr<SharedTree> shared, double budgetUs)
    : m_shared(std::move(shared)), m_budgetUs(budgetUs) {}

MethodParams BoxFirstMethod::params() const {
  MethodParams p;
  p.budgetUs = m_budgetUs;
  return p;  // no estimate: its confidence is 1 (completed) or a fixed 0.5 (cut)
}

void BoxFirstMethod::prepare(const Model& a, const Model& b) {
  m_shared->prepare(a, b);
  m_treeA = &m_shared->treeFor(a);
  m_treeB = &m_shared->treeFor(b);
  m_boundsA = a.mesh.bounds();
  m_boundsB = b.mesh.bounds();
}

BoxFirstMethod::Frame BoxFirstMethod::frameBetween(const Pose& a, const Pose& b) const {
  // World placement of the tree's local frame: world = R (x_local + origin) + t.
  const Vec3 ta = a.apply(m_treeA->origin());
  const Vec3 tb = b.apply(m_treeB->origin());
  // Exact inverses, not transposes: study poses are orthonormal only to rounding, and the
  // two directions must describe the same placement.
  const Mat3 worldToA = a.rotation.inverse();
  Frame f;
  f.rBA = worldToA * b.rotation;
  f.tBA = worldToA * (tb - ta);
  f.rAB = f.rBA.inverse();
  f.tAB = -(f.rAB * f.tBA);
  f.absBA = f.rBA.cwiseAbs();
  f.absAB = f.rAB.cwiseAbs();
  const auto radius = [](const Node& root) {
    return std::max(root.boxLo().cwiseAbs().maxCoeff(), root.boxHi().cwiseAbs().maxCoeff());
  };
  f.slack = kRelativeSlack * (f.tBA.norm() + (radius(m_treeA->root()) + radius(m_treeB->root())));
  return f;
}

bool BoxFirstMethod::leavesIntersect(const Node& na, const Node& nb, const Frame& f,
                                     Budget& budget) const {
  const auto& va = m_treeA->localVertices();
  const auto& ta = m_treeA->triangles();
  const auto& vb = m_treeB->localVertices();
  const auto& tb = m_treeB->triangles();
  // B's triangles mapped into A's frame, and the boxes of both leaves' triangles there, once
  // per leaf pair (a leaf holds at most 15; the slots a leaf does not use stay unwritten).
  Vec3 mapped[15][3];
  Vec3 loA[15], hiA[15], loB[15], hiB[15];
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::uint32_t j = 0; j < nb.triangleCount(); ++j) {
    for (int k = 0; k < 3; ++k) mapped[j][k] = f.bToA(vb[tb[nb.firstTriangle() + j][k]]);
    loB[j] = mapped[j][0].cwiseMin(mapped[j][1]).cwiseMin(mapped[j][2]);
    hiB[j] = mapped[j][0].cwiseMax(mapped[j][1]).cwiseMax(mapped[j][2]);
    lo = lo.cwiseMin(loB[j]);
    hi = hi.cwiseMax(hiB[j]);
  }
  for (std::uint32_t i = 0; i < na.triangleCount(); ++i) {
    const Triangle& tri = ta[na.firstTriangle() + i];
    loA[i] = va[tri[0]].cwiseMin(va[tri[1]]).cwiseMin(va[tri[2]]);
    hiA[i] = va[tri[0]].cwiseMax(va[tri[1]]).cwiseMax(va[tri[2]]);
    lo = lo.cwiseMin(loA[i]);
    hi = hi.cwiseMax(hiA[i]);
  }
  const double gap = kTriangleGap * (hi - lo).maxCoeff();
  for (std::uint32_t i = 0; i < na.triangleCount(); ++i) {
    const Triangle& tri = ta[na.firstTriangle() + i];
    for (std::uint32_t j = 0; j < nb.triangleCount(); ++j) {
      if (boxesApart(loA[i], hiA[i], loB[j], hiB[j], gap)) continue;
      budget.countTriangleTest();
      if (trianglesIntersect(va[tri[0]], va[tri[1]], va[tri[2]], mapped[j][0], mapped[j][1],
                             mapped[j][2])) {
        return true;
      }
    }
  }
  return false;
}

void BoxFirstMethod::pushOverlappingChildren(const Entry& e, const Frame& f,
                                             std::int64_t& nodePairs) {
  std::uint32_t ca[2], cb[2];
  const int countA = children(m_treeA->nodes()[e.a], e.a, ca);
  const int countB = children(m_treeB->nodes()[e.b], e.b, cb);
  // Every child's box mapped into the other frame first: a child meets both children of the
  // other node, and the mapping is most of a pair test's cost.
  MappedBox a[2], b[2];
  for (int i = 0; i < countA; ++i) a[i] = mapBox(m_treeA->nodes()[ca[i]], f.rAB, f.absAB, f.tAB);
  for (int j = 0; j < countB; ++j) b[j] = mapBox(m_treeB->nodes()[cb[j]], f.rBA, f.absBA, f.tBA);
  for (int i = 0; i < countA; ++i) {
    for (int j = 0; j < countB; ++j) {
      ++nodePairs;
      const double key = overlapKey(a[i], b[j], f.slack);
      if (key < 0.0) continue;
      m_heap.push_back(Entry{key, ca[i], cb[j]});
      std::push_heap(m_heap.begin(), m_heap.end(), heapLess);
    }
  }
}

bool BoxFirstMethod::expand(const Entry& e, const Frame& f, Budget& budget,
                            std::int64_t& nodePairs) {
  const Node& na = m_treeA->nodes()[e.a];
  const Node& nb = m_treeB->nodes()[e.b];
  if (na.isLeaf() && nb.isLeaf()) return leavesIntersect(na, nb, f, budget);
  pushOverlappingChildren(e, f, nodePairs);
  return false;
}

Answer BoxFirstMethod::query(const Pose& a, const Pose& b) {
  Budget budget(m_budgetUs);  // starts the clock
  m_heap.clear();  // keeps its capacity: no allocation once grown
  Answer answer;   // "no collision", certain, until shown otherwise
  answer.nodePairs = 1;  // the roots' test
  if (!rootBoxesOverlap(m_boundsA, a, m_boundsB, b)) return answer;
  const Frame f = frameBetween(a, b);
  m_heap.push_back(Entry{0.0, 0, 0});  // alone in the queue: its key is never compared
  while (!m_heap.empty()) {
    if (budget.spent()) {
      answer.collides = true;  // boxes still overlap: all it can say without probability
      answer.confidence = 0.5;
      return answer;
    }
    std::pop_heap(m_heap.begin(), m_heap.end(), heapLess);
    const Entry e = m_heap.back();
    m_heap.pop_back();
    if (expand(e, f, budget, answer.nodePairs)) {
      answer.collides = true;  // an intersecting triangle pair: certain
      return answer;
    }
  }
  return answer;
}

}  // namespace adb::tradeoff
