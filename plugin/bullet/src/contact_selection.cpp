// ContactSelection: the deepest candidate, then the widest support.
#include "contact_selection.h"

#include <algorithm>
#include <utility>

namespace adb::detail {

const CandidateContact* ContactSelection::closest() const {
  const CandidateContact* best = nullptr;
  for (int i = 0; i < m_count; ++i) {
    if (!best || m_candidates[i].distance < best->distance) best = &m_candidates[i];
  }
  return best;
}

void ContactSelection::add(const CandidateContact& c) {
  // Once full, the candidates form a heap with the shallowest on top: a deeper candidate
  // replaces it in O(log n).
  const auto shallower = [](const CandidateContact& x, const CandidateContact& y) {
    return x.distance < y.distance;
  };
  if (m_count < kCapacity) {
    m_candidates[m_count++] = c;
    if (m_count == kCapacity) std::make_heap(m_candidates, m_candidates + m_count, shallower);
    return;
  }
  if (!(c.distance < m_candidates[0].distance)) return;
  std::pop_heap(m_candidates, m_candidates + m_count, shallower);
  m_candidates[m_count - 1] = c;
  std::push_heap(m_candidates, m_candidates + m_count, shallower);
}

namespace {

// The support: points within this fraction of the breaking threshold of the deepest one.
// A resting face touches at depths that differ by rounding and the solver's slop; a vertex
// hovering 0.01 above a plane (inside the 0.02 breaking distance) is not part of it.
constexpr btScalar kSupportBand = btScalar(0.25);

}  // namespace

int ContactSelection::write(btManifoldResult& result, bool meshIsBody0,
                            const btPersistentManifold& previous) {
  if (m_count == 0) return 0;
  int deepest = 0;
  for (int i = 1; i < m_count; ++i) {
    if (m_candidates[i].distance < m_candidates[deepest].distance) deepest = i;
  }
  std::swap(m_candidates[0], m_candidates[deepest]);
  // The support band, moved to the front: [0, support).
  const btScalar threshold = previous.getContactBreakingThreshold();
  // So is every candidate deeper than the breaking threshold: a body pressed that deep into
  // a floor (a stack's bottom gear, 0.18 into a plane) touches wherever it is inside, not
  // only where it is deepest, and a support of the deepest few points let it tip through.
  // (Every penetrating candidate was too many: a body resting on a plane rocked between
  // supports, 0.066 m/s after 10 s in PlaneRest.)
  const btScalar limit =
      btMax(m_candidates[0].distance + kSupportBand * threshold, -threshold);
  int support = 1;
  for (int i = 1; i < m_count; ++i) {
    if (m_candidates[i].distance <= limit) std::swap(m_candidates[support++], m_candidates[i]);
  }
  // Bullet merges a new point into a cached one closer than the breaking threshold: a point
  // written that close to one already written would replace it (the deepest, say). Every
  // point written is farther than that from the others.
  const btScalar apart = threshold * threshold;
  btScalar nearest[kCapacity];  // squared distance to the nearest chosen point
  for (int i = 1; i < support; ++i) {
    nearest[i] = (m_candidates[i].pointOnB - m_candidates[0].pointOnB).length2();
  }
  int chosen = 1;
  const auto choose = [&](int best) {
    std::swap(m_candidates[chosen], m_candidates[best]);
    std::swap(nearest[chosen], nearest[best]);
    for (int i = chosen + 1; i < support; ++i) {
      nearest[i] = btMin(nearest[i],
                         (m_candidates[i].pointOnB - m_candidates[chosen].pointOnB).length2());
    }
    ++chosen;
  };
  // Persistence: the candidate nearest each of last step's points, so Bullet matches it.
  for (int k = 0; k < previous.getNumContacts() && chosen < kWritten; ++k) {
    const btVector3& old = previous.getContactPoint(k).m_positionWorldOnB;
    int best = -1;
    btScalar bestDistance = apart;
    for (int i = chosen; i < support; ++i) {
      const btScalar d = (m_candidates[i].pointOnB - old).length2();
      if (d < bestDistance && nearest[i] > apart) {
        bestDistance = d;
        best = i;
      }
    }
    if (best >= 0) choose(best);
  }
  // Greedy farthest-point selection over the rest of the support: each next point maximises
  // its distance to the nearest one already chosen.
  while (chosen < kWritten && chosen < support) {
    int best = chosen;
    for (int i = chosen + 1; i < support; ++i) {
      if (nearest[i] > nearest[best]) best = i;
    }
    if (!(nearest[best] > apart)) break;  // the rest would merge with chosen points
    choose(best);
  }
  for (int i = 0; i < chosen; ++i) {
    const CandidateContact& c = m_candidates[i];
    if (meshIsBody0) {
      result.setShapeIdentifiersA(0, c.meshTriangle);
    } else {
      result.setShapeIdentifiersB(0, c.meshTriangle);
    }
    result.addContactPoint(c.normalOnB, c.pointOnB, c.distance);
  }
  m_count = 0;
  return chosen;
}

}  // namespace adb::detail
