#include "pair_kernel.h"

#include <algorithm>
#include <cmath>

#include "adb/core/probability.h"

namespace adb::detail {
namespace {

// round(x) for x >= 0 (truncating x + 0.5: without SSE4.1, floor would be a library call per
// count), 0 for x <= 0 or NaN, at most `cap`.
Lanes roundCount(Lanes x, Lanes cap) {
  const Lanes rounded = truncated(min(x + Lanes::all(0.5), cap));
  return select(x > Lanes::all(0.0), rounded, Lanes::all(0.0));
}

}  // namespace

unsigned PairKernel::measure(double separation[4]) {
  const unsigned mask = overlapMask();
  mapA();
  slabs();
  unsigned overlaps = 0;
  measureRow<0>(m_frame.slack, mask, separation, overlaps);
  if (m_a.count == 2) measureRow<1>(m_frame.slack, mask, separation, overlaps);
  return overlaps;
}

template <int I>
void PairKernel::measureRow(double slack, unsigned mask, double separation[4],
                            unsigned& overlaps) const {
  Lanes inA{}, inB{};
  for (int k = 0; k < 3; ++k) {
    const Lanes gapA = abs(m_b.cOther[k] - m_a.c[k].broadcast(I)) - m_a.h[k].broadcast(I) -
                       m_b.hOther[k];
    const Lanes gapB = abs(m_a.cOther[k].broadcast(I) - m_b.c[k]) - m_b.h[k] -
                       m_a.hOther[k].broadcast(I);
    inA = k == 0 ? gapA : max(inA, gapA);
    inB = k == 0 ? gapB : max(inB, gapB);
  }
  const Lanes slabA = slabOffsetOfA<I>() - slabReachOfA<I>();
  const Lanes slabB = slabOffsetOfB<I>() - slabReachOfB<I>();
  const Lanes sep = max(max(inA, inB), max(slabA, slabB)) - Lanes::all(slack);
  for (int j = 0; j < m_b.count; ++j) {
    const int p = index(I, j);
    separation[p] = sep.lane(j);
    // The mask and the measure sum the same terms in another order: they can disagree only
    // within a few ulps of the scene's magnitude, far inside the slack (1e-12 of it). Outside
    // that band the sign decides; inside it, the mask, so that a walk and a descent agree.
    const bool overlap = std::abs(separation[p]) > slack ? separation[p] <= 0.0
                                                          : ((mask >> p) & 1u) != 0;
    if (overlap) overlaps |= 1u << p;
  }
}

void PairKernel::boxDepths(double depth[4]) const {
  for (int i = 0; i < m_a.count; ++i) {
    Lanes deepest{};
    for (int k = 0; k < 3; ++k) {
      const Lanes inA = m_a.h[k].broadcast(i) + m_b.hOther[k] -
                        abs(m_b.cOther[k] - m_a.c[k].broadcast(i));
      const Lanes inB = m_b.h[k] + m_a.hOther[k].broadcast(i) -
                        abs(m_a.cOther[k].broadcast(i) - m_b.c[k]);
      deepest = k == 0 ? min(inA, inB) : min(deepest, min(inA, inB));
    }
    deepest = max(deepest, Lanes::all(0.0));
    for (int j = 0; j < m_b.count; ++j) depth[index(i, j)] = deepest.lane(j);
  }
}

void PairKernel::cellCounts(unsigned mask, CellCounts counts[4]) const {
  const Lanes one = Lanes::all(1.0);
  for (int i = 0; i < m_a.count; ++i) {
    if ((mask & (3u << (2 * i))) == 0) continue;
    // The cell side is the coarser node's, per pair.
    const Lanes sideA = Lanes::all(m_a.d[i]->side);
    const Lanes sideB = Lanes::of(m_b.d[0]->side, m_b.d[1]->side);
    const Lanes invCell = select(sideA >= sideB, Lanes::all(m_a.d[i]->invSide),
                                 Lanes::of(m_b.d[0]->invSide, m_b.d[1]->invSide));
    // Cells touched by the boxes' intersection in A's frame and in B's, at least one per axis.
    Lanes inA{}, inB{};
    for (int k = 0; k < 3; ++k) {
      const Lanes ca = m_a.c[k].broadcast(i), ha = m_a.h[k].broadcast(i);
      const Lanes cao = m_a.cOther[k].broadcast(i), hao = m_a.hOther[k].broadcast(i);
      const Lanes extentA = min(ca + ha, m_b.cOther[k] + m_b.hOther[k]) -
                            max(ca - ha, m_b.cOther[k] - m_b.hOther[k]);
      const Lanes extentB =
          min(m_b.c[k] + m_b.h[k], cao + hao) - max(m_b.c[k] - m_b.h[k], cao - hao);
      const Lanes cellsA = max(extentA * invCell, one);
      const Lanes cellsB = max(extentB * invCell, one);
      inA = k == 0 ? cellsA : inA * cellsA;
      inB = k == 0 ? cellsB : inB * cellsB;
    }
    const Lanes touched = min(inA, inB);
    // The densities at the common cell size (pair_probability.cpp, step 3), then the counts.
    const LaneMask aCoarser = sideA >= sideB;
    const NodeDistribution& da = *m_a.d[i];
    const Lanes densityA = Lanes::all(da.density), invA = Lanes::all(da.invSide);
    const Lanes densityB = Lanes::of(m_b.d[0]->density, m_b.d[1]->density);
    const Lanes invB = Lanes::of(m_b.d[0]->invSide, m_b.d[1]->invSide);
    const Lanes rhoA = select(aCoarser, densityA, min(densityA * sideB * invA, one));
    const Lanes rhoB = select(aCoarser, min(densityB * sideA * invB, one), densityB);
    const Lanes cap = Lanes::all(kMaxBins);
    const Lanes s = max(roundCount(touched, cap), one);
    const Lanes sA = min(s, roundCount(rhoA * s, cap));
    const Lanes sB = min(s, roundCount(rhoB * s, cap));
    const Lanes expected = rhoA * rhoB * s;
    int si[2], sAi[2], sBi[2];
    toInts(s, si);
    toInts(sA, sAi);
    toInts(sB, sBi);
    for (int j = 0; j < m_b.count; ++j) {
      const int p = index(i, j);
      if (((mask >> p) & 1u) == 0) continue;
      counts[p] = CellCounts{si[j], sAi[j], sBi[j], expected.lane(j)};
    }
  }
}

}  // namespace adb::detail
