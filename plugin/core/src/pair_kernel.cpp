#include "pair_kernel.h"

#include "node_occupancy.h"

#include <algorithm>
#include <cmath>

#include "adb/core/probability.h"

namespace adb::detail {

// The boxes each node of pair (i, j) is tested in: B's node j posed in A's frame, and A's
// node i posed in B's, each grown by `grow`.
void PairKernel::reachedBoxes(int i, int j, double grow, Vec3 inA[2], Vec3 inB[2]) const {
  for (int k = 0; k < 3; ++k) {
    inA[0][k] = m_b.cOther[k].lane(j) - m_b.hOther[k].lane(j) - grow;
    inA[1][k] = m_b.cOther[k].lane(j) + m_b.hOther[k].lane(j) + grow;
    inB[0][k] = m_a.cOther[k].lane(i) - m_a.hOther[k].lane(i) - grow;
    inB[1][k] = m_a.cOther[k].lane(i) + m_a.hOther[k].lane(i) + grow;
  }
}

unsigned PairKernel::cellsApart(unsigned mask, double grow) const {
  unsigned apart = 0;
  for (int i = 0; i < m_a.count; ++i) {
    for (int j = 0; j < m_b.count; ++j) {
      const int p = index(i, j);
      if (((mask >> p) & 1u) == 0) continue;
      Vec3 inA[2], inB[2];
      reachedBoxes(i, j, grow, inA, inB);
      if (!occupiedWithin(*m_a.node[i], *m_a.cells[i], inA[0], inA[1]) ||
          !occupiedWithin(*m_b.node[j], *m_b.cells[j], inB[0], inB[1])) {
        apart |= 1u << p;
      }
    }
  }
  return apart;
}

double PairKernel::occupiedFill(int i, int j) const {
  Vec3 inA[2], inB[2];
  reachedBoxes(i, j, m_frame.slack, inA, inB);
  return detail::occupiedFill(*m_a.node[i], *m_a.cells[i], inA[0], inA[1]) *
         detail::occupiedFill(*m_b.node[j], *m_b.cells[j], inB[0], inB[1]);
}

unsigned PairKernel::measure(double separation[4]) {
  const unsigned mask = boxAndSlabMask();
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

}  // namespace adb::detail
