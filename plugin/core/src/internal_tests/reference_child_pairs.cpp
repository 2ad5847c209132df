#include "reference_child_pairs.h"

#include <algorithm>
#include <cmath>

#include "adb/core/probability.h"

namespace adb::reference {
namespace {

// Cells of side 1 / invCell touched by the intersection of box (c, h) with box (oc, oh) of
// the same frame; at least one per axis.
double touchedCells(const Vec3& c, const Vec3& h, const Vec3& oc, const Vec3& oh,
                    double invCell) {
  const Vec3 lo = (c - h).cwiseMax(oc - oh);
  const Vec3 hi = (c + h).cwiseMin(oc + oh);
  return ((hi - lo) * invCell).cwiseMax(Vec3::Ones()).prod();
}

int roundCount(double x, int cap) {
  // x is finite and >= 0 by construction; the cap keeps a corrupt value from overflowing. For
  // x >= 0 truncation is floor, which without SSE4.1 would be a library call per count.
  if (!(x > 0.0)) return 0;
  const double capped = std::min(x + 0.5, static_cast<double>(cap));
  return static_cast<int>(capped);
}

// Node `self`'s slab against the other node's box: the box's centre seen in self's frame, and
// its radius along self's slab normal (self.slabReach . the other's own half extents).
// How far the other box's centre lies from self's slab's mid-plane.
double slabOffset(const PosedNode& self, const PosedNode& other) {
  const NodeDistribution& d = *self.d;
  const double centre = d.normal[0] * other.cOther[0] + d.normal[1] * other.cOther[1] +
                        d.normal[2] * other.cOther[2];
  return std::abs(centre - d.offset);
}

// The slab's half width plus the other box's radius along its normal.
double slabReachOf(const PosedNode& self, const PosedNode& other) {
  return self.d->halfWidth + self.slabReach.dot(other.h);
}

bool slabOverlaps(const PosedNode& self, const PosedNode& other, double slack) {
  return slabOffset(self, other) <= slabReachOf(self, other) + slack;
}

}  // namespace

detail::CellCounts countsOverlapping(const PosedNode& a, const PosedNode& b) {
  detail::CellCounts e;
  const NodeDistribution& cellsA = *a.d;
  const NodeDistribution& cellsB = *b.d;
  const bool aCoarser = cellsA.side >= cellsB.side;
  const double invCell = aCoarser ? cellsA.invSide : cellsB.invSide;
  const double touched = std::min(touchedCells(a.c, a.h, b.cOther, b.hOther, invCell),
                                  touchedCells(b.c, b.h, a.cOther, a.hOther, invCell));
  e.s = std::max(1, roundCount(touched, kMaxBins));
  const double rhoA =
      aCoarser ? cellsA.density
               : std::min(1.0, static_cast<double>(cellsA.density) * cellsB.side * cellsA.invSide);
  const double rhoB =
      aCoarser ? std::min(1.0, static_cast<double>(cellsB.density) * cellsA.side * cellsB.invSide)
               : cellsB.density;
  e.sA = std::min(e.s, roundCount(rhoA * e.s, kMaxBins));
  e.sB = std::min(e.s, roundCount(rhoB * e.s, kMaxBins));
  e.expected = rhoA * rhoB * e.s;
  return e;
}

ChildPairs::ChildPairs(const AdbTree& a, const std::uint32_t* ca, int countA, const AdbTree& b,
                       const std::uint32_t* cb, int countB, const detail::RelativeFrame& frame)
    : m_frame(frame),
      m_rBAt(frame.rBA.transpose()),
      m_rABt(frame.rAB.transpose()),
      m_absBA(frame.rBA.cwiseAbs()),
      m_absAB(frame.rAB.cwiseAbs()) {
  for (int i = 0; i < countA; ++i) {
    const Node& n = a.nodes()[ca[i]];
    m_a[i].c = 0.5 * (n.boxHi() + n.boxLo());
    m_a[i].h = 0.5 * (n.boxHi() - n.boxLo());
    m_a[i].d = &a.distributions()[ca[i]];
  }
  for (int j = 0; j < countB; ++j) {
    const Node& n = b.nodes()[cb[j]];
    PosedNode& p = m_b[j];
    p.c = 0.5 * (n.boxHi() + n.boxLo());
    p.h = 0.5 * (n.boxHi() - n.boxLo());
    p.d = &b.distributions()[cb[j]];
    p.cOther = mul(frame.rBA, p.c) + frame.tBA;
    p.hOther = mul(m_absBA, p.h);
  }
}

void ChildPairs::mapA(int i) {
  if (m_mappedA[i]) return;
  m_mappedA[i] = true;
  m_a[i].cOther = mul(m_frame.rAB, m_a[i].c) + m_frame.tAB;
  m_a[i].hOther = mul(m_absAB, m_a[i].h);
}

void ChildPairs::reachA(int i) {
  if (m_reachA[i]) return;
  m_reachA[i] = true;
  const NodeDistribution& d = *m_a[i].d;
  m_a[i].slabReach = mul(m_rBAt, Vec3(d.normal[0], d.normal[1], d.normal[2])).cwiseAbs();
}

void ChildPairs::reachB(int j) {
  if (m_reachB[j]) return;
  m_reachB[j] = true;
  const NodeDistribution& d = *m_b[j].d;
  m_b[j].slabReach = mul(m_rABt, Vec3(d.normal[0], d.normal[1], d.normal[2])).cwiseAbs();
}

// Boxes on both frames' face axes, then slabs: a curved sheet's nodes are thin along their
// mean normal, so the slab rejects near misses the boxes cannot (measured in
// docs/core-results.md). The 9 edge-edge axes would prune a few more pairs at twice the cost.
bool ChildPairs::overlap(int i, int j) {
  const PosedNode& pa = m_a[i];
  const PosedNode& pb = m_b[j];
  const double slack = m_frame.slack;
  const Vec3 dA = (pb.cOther - pa.c).cwiseAbs();
  if ((dA.array() > (pa.h + pb.hOther).array() + slack).any()) return false;
  mapA(i);
  const Vec3 dB = (pa.cOther - pb.c).cwiseAbs();
  if ((dB.array() > (pb.h + pa.hOther).array() + slack).any()) return false;
  reachA(i);
  if (!slabOverlaps(pa, pb, slack)) return false;
  reachB(j);
  return slabOverlaps(pb, pa, slack);
}

double ChildPairs::overlapDepth(int i, int j) {
  return overlap(i, j) ? boxDepth(i, j) : -1.0;
}

double ChildPairs::boxDepth(int i, int j) const {
  const PosedNode& pa = m_a[i];
  const PosedNode& pb = m_b[j];
  const Vec3 inA = pa.h + pb.hOther - (pb.cOther - pa.c).cwiseAbs();
  const Vec3 inB = pb.h + pa.hOther - (pa.cOther - pb.c).cwiseAbs();
  return std::max(0.0, std::min(inA.minCoeff(), inB.minCoeff()));
}

double ChildPairs::separation(int i, int j) {
  mapA(i);
  reachA(i);
  reachB(j);
  const PosedNode& pa = m_a[i];
  const PosedNode& pb = m_b[j];
  const double inA = ((pb.cOther - pa.c).cwiseAbs() - pa.h - pb.hOther).maxCoeff();
  const double inB = ((pa.cOther - pb.c).cwiseAbs() - pb.h - pa.hOther).maxCoeff();
  const double slabA = slabOffset(pa, pb) - slabReachOf(pa, pb);
  const double slabB = slabOffset(pb, pa) - slabReachOf(pb, pa);
  return std::max(std::max(inA, inB), std::max(slabA, slabB)) - m_frame.slack;
}

PairTest ChildPairs::test(int i, int j) {
  const double separation = this->separation(i, j);
  // overlap() sums the same terms in another order: the two can disagree only within a few
  // ulps of the scene's magnitude, far inside the slack (1e-12 of it). Outside that band the
  // sign decides; inside it, overlap()'s answer, so that a walk and a descent agree.
  const bool overlaps =
      std::abs(separation) > m_frame.slack ? separation <= 0.0 : overlap(i, j);
  return {overlaps, separation};
}

}  // namespace adb::reference
