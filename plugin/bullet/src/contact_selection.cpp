// ContactSelection: the deepest candidate, then the widest support.
#include "contact_selection.h"

#include <algorithm>
#include <utility>

namespace adb::detail {

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

int ContactSelection::write(btManifoldResult& result, bool meshIsBody0) {
  if (m_count == 0) return 0;
  // Greedy farthest-point selection, seeded with the deepest: each next point maximises its
  // distance to the nearest one already chosen (the chosen ones swap to the front).
  int deepest = 0;
  for (int i = 1; i < m_count; ++i) {
    if (m_candidates[i].distance < m_candidates[deepest].distance) deepest = i;
  }
  std::swap(m_candidates[0], m_candidates[deepest]);
  btScalar nearest[kCapacity];
  for (int i = 1; i < m_count; ++i) {
    nearest[i] = (m_candidates[i].pointOnB - m_candidates[0].pointOnB).length2();
  }
  int chosen = 1;
  while (chosen < kWritten && chosen < m_count) {
    int best = chosen;
    for (int i = chosen + 1; i < m_count; ++i) {
      if (nearest[i] > nearest[best]) best = i;
    }
    if (!(nearest[best] > 0)) break;  // the rest coincide with chosen points
    std::swap(m_candidates[chosen], m_candidates[best]);
    std::swap(nearest[chosen], nearest[best]);
    for (int i = chosen + 1; i < m_count; ++i) {
      nearest[i] = btMin(nearest[i],
                         (m_candidates[i].pointOnB - m_candidates[chosen].pointOnB).length2());
    }
    ++chosen;
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
