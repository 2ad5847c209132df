// reduceContacts: the deepest point, the points that were there last step, the widest support.
#include "contact_reduction.h"

#include <algorithm>
#include <utility>

namespace adb::detail {
namespace {

// The point on body A of a contact as Bullet writes it (btManifoldResult::addContactPoint):
// its matching runs on these.
btVector3 pointOnA(const PendingContact& c) { return c.pointOnB + c.normalOnB * c.distance; }

// The deepest first; equal depths by their features, so that the order never depends on
// the order the traversal found them in.
bool deeper(const PendingContact& x, const PendingContact& y) {
  if (x.distance != y.distance) return x.distance < y.distance;
  if (x.featureA != y.featureA) return x.featureA < y.featureA;
  return x.featureB < y.featureB;
}

}  // namespace

void reduceContacts(ContactPoints& points, const ContactGroups& groups) {
  const int capacity = groups.count * kManifoldPoints;
  const btScalar threshold = groups.manifolds[0]->getContactBreakingThreshold();
  // The manifold's candidates first, [0, candidates), the speculative ones after.
  const auto speculative = std::partition(points.begin(), points.end(), [&](const PendingContact& c) {
    return c.distance <= threshold;
  });
  const int candidates = static_cast<int>(speculative - points.begin());
  if (candidates == 0) return;
  std::sort(points.begin(), speculative, deeper);
  // nearest[i]: squared distance on A from candidate i to the nearest point chosen so far.
  // Chosen points are swapped into [0, chosen).
  const btScalar apart = threshold * threshold;
  constexpr int kCapacity = 128;  // more candidates than a pair makes (64 exact, 32 plausible)
  const int considered = std::min(candidates, kCapacity);
  btScalar nearest[kCapacity];
  const btVector3 first = pointOnA(points[0]);
  for (int i = 1; i < considered; ++i) nearest[i] = (pointOnA(points[i]) - first).length2();
  int chosen = 1;
  const auto choose = [&](int best) {
    std::swap(points[chosen], points[best]);
    std::swap(nearest[chosen], nearest[best]);
    const btVector3 at = pointOnA(points[chosen]);
    for (int i = chosen + 1; i < considered; ++i) {
      nearest[i] = btMin(nearest[i], (pointOnA(points[i]) - at).length2());
    }
    ++chosen;
  };
  // Persistence: last step's points whose features are still in contact, in their order.
  for (int g = 0; g < groups.count; ++g) {
    const btPersistentManifold& previous = *groups.manifolds[g];
    for (int k = 0; k < previous.getNumContacts() && chosen < capacity; ++k) {
      const btManifoldPoint& old = previous.getContactPoint(k);
      for (int i = chosen; i < considered; ++i) {
        const PendingContact& c = points[static_cast<std::size_t>(i)];
        const bool same = c.featureA == old.m_index0 && c.featureB == old.m_index1;
        if (same && nearest[i] > apart) {
          choose(i);
          break;
        }
      }
    }
  }
  // The widest support: each next point the farthest from those chosen.
  while (chosen < capacity && chosen < considered) {
    int best = chosen;
    for (int i = chosen + 1; i < considered; ++i) {
      if (nearest[i] > nearest[best]) best = i;
    }
    if (!(nearest[best] > apart)) break;  // the rest would merge into chosen points
    choose(best);
  }
  // Keep [0, chosen) and the speculative points.
  const auto kept = std::move(speculative, points.end(), points.begin() + chosen);
  points.erase(kept, points.end());
}

}  // namespace adb::detail
