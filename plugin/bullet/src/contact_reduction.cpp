// reduceContacts: the deepest point, the points that were there last step, the widest support.
#include "contact_reduction.h"

#include <algorithm>
#include <limits>
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

// Exact points before plausible ones (a plausible point guesses where the surfaces may
// meet; an exact one is where they do), each kind deepest first.
bool exactThenDeeper(const PendingContact& x, const PendingContact& y) {
  if (x.softened != y.softened) return !x.softened;
  return deeper(x, y);
}

// Last step's exact points (two triangles' ids) that no exact candidate of this step has:
// the places a cut query did not reach again this step.
int exactPointsNotFoundAgain(const ContactPoints& points, int candidates,
                             const ContactGroups& groups) {
  int count = 0;
  for (int g = 0; g < groups.count; ++g) {
    const btPersistentManifold& previous = *groups.manifolds[g];
    for (int k = 0; k < previous.getNumContacts(); ++k) {
      const btManifoldPoint& old = previous.getContactPoint(k);
      if (old.m_index0 < 0 || old.m_index1 < 0) continue;
      bool found = false;
      for (int i = 0; i < candidates && !found; ++i) {
        const PendingContact& c = points[static_cast<std::size_t>(i)];
        found = !c.softened && c.featureA == old.m_index0 && c.featureB == old.m_index1;
      }
      count += found ? 0 : 1;
    }
  }
  return count;
}

}  // namespace

void reduceContacts(ContactPoints& points, const ContactGroups& groups, bool cut) {
  const int capacity = groups.count * kManifoldPoints;
  const btScalar threshold = groups.manifolds[0]->getContactBreakingThreshold();
  // The manifold's candidates first, [0, candidates), the speculative ones after.
  const auto speculative = std::partition(points.begin(), points.end(), [&](const PendingContact& c) {
    return c.distance <= threshold;
  });
  const int candidates = static_cast<int>(speculative - points.begin());
  if (candidates == 0) return;
  std::sort(points.begin(), speculative, exactThenDeeper);
  // A cut query leaves last step's exact points it did not reach again to the writer, which
  // keeps them, re-measured: this step's new points take only the room they leave.
  const int room = capacity - (cut ? exactPointsNotFoundAgain(points, candidates, groups) : 0);
  // nearest[i]: squared distance on A from candidate i to the nearest point chosen so far.
  // Chosen points are swapped into [0, chosen).
  const btScalar apart = threshold * threshold;
  constexpr int kCapacity = 128;  // more candidates than a pair makes (64 exact, 32 plausible)
  const int considered = std::min(candidates, kCapacity);
  btScalar nearest[kCapacity];
  std::fill(nearest, nearest + considered, std::numeric_limits<btScalar>::infinity());
  int chosen = 0;
  const auto choose = [&](int best) {
    std::swap(points[chosen], points[best]);
    std::swap(nearest[chosen], nearest[best]);
    const btVector3 at = pointOnA(points[chosen]);
    for (int i = chosen + 1; i < considered; ++i) {
      nearest[i] = btMin(nearest[i], (pointOnA(points[i]) - at).length2());
    }
    ++chosen;
  };
  // Whether candidate i may still be chosen: apart from the chosen ones, within the room.
  // A plausible point only where the pair knows no exact one, this step's or kept: it
  // guesses where the surfaces may meet, and a guess beside a known contact only pushes.
  const bool knowsExact = room < capacity || !points[0].softened;  // sorted: exact first
  const auto eligible = [&](int i) {
    if (!(chosen < room && nearest[i] > apart)) return false;
    return !(knowsExact && points[static_cast<std::size_t>(i)].softened);
  };
  // Persistence: last step's points whose features are still in contact, in their order.
  const auto persist = [&] {
    for (int g = 0; g < groups.count; ++g) {
      const btPersistentManifold& previous = *groups.manifolds[g];
      for (int k = 0; k < previous.getNumContacts(); ++k) {
        const btManifoldPoint& old = previous.getContactPoint(k);
        for (int i = chosen; i < considered; ++i) {
          const PendingContact& c = points[static_cast<std::size_t>(i)];
          const bool same = c.featureA == old.m_index0 && c.featureB == old.m_index1;
          if (same && eligible(i)) {
            choose(i);
            break;
          }
        }
      }
    }
  };
  // The deepest point (exact ones first) stops the bodies sinking; a cut pair's points of
  // last step come first (those it found again, and those the writer keeps), so that a cut
  // pair at rest writes the same points every step.
  if (cut) persist();
  for (int i = chosen; i < considered && chosen == 0; ++i) {
    if (eligible(i)) choose(i);
  }
  if (!cut) persist();
  // The widest support: each next point the farthest from those chosen, exact ones first.
  while (chosen < room && chosen < considered) {
    int best = -1;
    for (int i = chosen; i < considered; ++i) {
      if (!eligible(i)) continue;
      const PendingContact& c = points[static_cast<std::size_t>(i)];
      if (best < 0) {
        best = i;
        continue;
      }
      const PendingContact& b = points[static_cast<std::size_t>(best)];
      if (c.softened != b.softened ? !c.softened : nearest[i] > nearest[best]) best = i;
    }
    if (best < 0) break;  // the rest would merge into chosen points
    choose(best);
  }
  // Keep [0, chosen) and the speculative points.
  const auto kept = std::move(speculative, points.end(), points.begin() + chosen);
  points.erase(kept, points.end());
}

}  // namespace adb::detail
