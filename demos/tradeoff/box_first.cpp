// The box-first traversal (see box_first.h).
#include "box_first.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "adb/core/triangle_test.h"
#include "root_overlap.h"

namespace adb::tradeoff {

// Tree B's local frame seen from tree A's (both trees are the model's one tree, posed twice).
struct BoxFirstMethod::Frame {
  Mat3 rBA, absBA, rAB, absAB;
  Vec3 tBA, tAB;
  double slack = 0.0;  ///< absolute overlap tolerance for the rounding of the transform

  Vec3 bToA(const Vec3& x) const { return rBA * x + tBA; }
};

namespace {

using Clock = std::chrono::steady_clock;

// Rounding of the transform, relative to the scene's size (the core uses the same 1e-12):
// boxes that touch must not be separated by it.
constexpr double kRelativeSlack = 1e-12;

// Triangle pairs whose boxes are apart by more than this fraction of the leaf pair's extent
// are skipped untested: a thousand times trianglesIntersect's tolerance, so the test would
// have said "apart" too (the core's leaf test uses the same rule).
constexpr double kTriangleGap = 1e-9;

struct Box {
  Vec3 c, h;  // centre and half extents in the node's own (tree-local) frame
};

Box boxOf(const Node& n) {
  return Box{0.5 * (n.boxHi() + n.boxLo()), 0.5 * (n.boxHi() - n.boxLo())};
}

double microsSince(Clock::time_point start) {
  return std::chrono::duration<double, std::micro>(Clock::now() - start).count();
}

// Whether the intervals (centre c, half extent h) and (c2, h2) are apart on some axis.
bool apart(const Vec3& c, const Vec3& h, const Vec3& c2, const Vec3& h2, double slack) {
  return ((c2 - c).cwiseAbs().array() > (h + h2).array() + slack).any();
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

bool triangleBoxesApart(const Vec3 (&x)[3], const Vec3 (&y)[3], double gap) {
  const Vec3 loX = x[0].cwiseMin(x[1]).cwiseMin(x[2]), hiX = x[0].cwiseMax(x[1]).cwiseMax(x[2]);
  const Vec3 loY = y[0].cwiseMin(y[1]).cwiseMin(y[2]), hiY = y[0].cwiseMax(y[1]).cwiseMax(y[2]);
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

void BoxFirstMethod::prepare(const Model& model) {
  m_tree = &m_shared->treeFor(model);
  m_bounds = model.mesh.bounds();
}

BoxFirstMethod::Frame BoxFirstMethod::frameBetween(const Pose& a, const Pose& b) const {
  // World placement of the tree's local frame: world = R (x_local + origin) + t.
  const Vec3 ta = a.rotation * m_tree->origin() + a.translation;
  const Vec3 tb = b.rotation * m_tree->origin() + b.translation;
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
  const Node& root = m_tree->root();
  const double radius =
      std::max(root.boxLo().cwiseAbs().maxCoeff(), root.boxHi().cwiseAbs().maxCoeff());
  f.slack = kRelativeSlack * (f.tBA.norm() + 2.0 * radius);
  return f;
}

double BoxFirstMethod::overlapKey(std::uint32_t ia, std::uint32_t ib, const Frame& f) const {
  const Box a = boxOf(m_tree->nodes()[ia]);
  const Box b = boxOf(m_tree->nodes()[ib]);
  const Box bInA{f.bToA(b.c), f.absBA * b.h};  // the AABB of B's box in A's frame
  if (apart(a.c, a.h, bInA.c, bInA.h, f.slack)) return -1.0;
  if (apart(b.c, b.h, f.rAB * a.c + f.tAB, f.absAB * a.h, f.slack)) return -1.0;
  // Overlap volume in A's frame; >= 0 (touching boxes, within the slack, give 0).
  const Vec3 lo = (a.c - a.h).cwiseMax(bInA.c - bInA.h);
  const Vec3 hi = (a.c + a.h).cwiseMin(bInA.c + bInA.h);
  return (hi - lo).cwiseMax(Vec3::Zero()).prod();
}

bool BoxFirstMethod::leavesIntersect(const Node& na, const Node& nb, const Frame& f) const {
  const auto& v = m_tree->localVertices();
  const auto& t = m_tree->triangles();
  Vec3 mapped[15][3];  // B's triangles in A's frame (a leaf holds at most 15)
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::uint32_t j = 0; j < nb.triangleCount(); ++j) {
    for (int k = 0; k < 3; ++k) {
      mapped[j][k] = f.bToA(v[t[nb.firstTriangle() + j][k]]);
      lo = lo.cwiseMin(mapped[j][k]);
      hi = hi.cwiseMax(mapped[j][k]);
    }
  }
  for (std::uint32_t i = 0; i < na.triangleCount(); ++i) {
    for (int k = 0; k < 3; ++k) {
      lo = lo.cwiseMin(v[t[na.firstTriangle() + i][k]]);
      hi = hi.cwiseMax(v[t[na.firstTriangle() + i][k]]);
    }
  }
  const double gap = kTriangleGap * (hi - lo).maxCoeff();
  for (std::uint32_t i = 0; i < na.triangleCount(); ++i) {
    const Triangle& ta = t[na.firstTriangle() + i];
    const Vec3 own[3] = {v[ta[0]], v[ta[1]], v[ta[2]]};
    for (std::uint32_t j = 0; j < nb.triangleCount(); ++j) {
      if (triangleBoxesApart(own, mapped[j], gap)) continue;
      if (trianglesIntersect(own[0], own[1], own[2], mapped[j][0], mapped[j][1], mapped[j][2])) {
        return true;
      }
    }
  }
  return false;
}

bool BoxFirstMethod::expand(const Entry& e, const Frame& f, std::int64_t& nodePairs) {
  const Node& na = m_tree->nodes()[e.a];
  const Node& nb = m_tree->nodes()[e.b];
  if (na.isLeaf() && nb.isLeaf()) return leavesIntersect(na, nb, f);
  std::uint32_t ca[2], cb[2];
  const int countA = children(na, e.a, ca), countB = children(nb, e.b, cb);
  for (int i = 0; i < countA; ++i) {
    for (int j = 0; j < countB; ++j) {
      ++nodePairs;
      const double key = overlapKey(ca[i], cb[j], f);
      if (key < 0.0) continue;
      m_heap.push_back(Entry{key, ca[i], cb[j]});
      std::push_heap(m_heap.begin(), m_heap.end(), heapLess);
    }
  }
  return false;
}

Answer BoxFirstMethod::query(const Pose& a, const Pose& b) {
  const auto start = Clock::now();
  const bool timed = std::isfinite(m_budgetUs);
  m_heap.clear();  // keeps its capacity: no allocation once grown
  Answer answer;   // "no collision", certain, until shown otherwise
  answer.nodePairs = 1;  // the roots' test
  if (!rootBoxesOverlap(m_bounds, a, b)) return answer;
  const Frame f = frameBetween(a, b);
  m_heap.push_back(Entry{0.0, 0, 0});  // alone in the queue: its key is never compared
  for (std::uint64_t popped = 0; !m_heap.empty(); ++popped) {
    // The first read is at the first pop, so a budget of 0 stops before any work.
    if (timed && popped % kClockInterval == 0 && microsSince(start) >= m_budgetUs) {
      answer.collides = true;  // boxes still overlap: all it can say without probability
      answer.confidence = 0.5;
      return answer;
    }
    std::pop_heap(m_heap.begin(), m_heap.end(), heapLess);
    const Entry e = m_heap.back();
    m_heap.pop_back();
    if (expand(e, f, answer.nodePairs)) {
      answer.collides = true;  // an intersecting triangle pair: certain
      return answer;
    }
  }
  return answer;
}

}  // namespace adb::tradeoff
