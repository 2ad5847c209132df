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

// How many breaking thresholds deeper than every kept point this step's deepest exact point
// must be for a cut pair to make room for this step's points (reduceContacts). Measured on the
// 17 scenes at 1/4, 1/8 and 1/16 of the need (docs/bullet-results.md, "Floors that hold under
// any budget", with the commands): at 1 the new points churned and 9 fewer runs fell asleep;
// at 4 the runs were as before but for the mesh-bin gears, which lost 0 and 2 bodies at 1/8
// and 1/16 instead of 3 and 5.
constexpr btScalar kSinking = 4;

// Exact points before plausible ones (a plausible point guesses where the surfaces may
// meet; an exact one is where they do), each kind deepest first.
bool exactThenDeeper(const PendingContact& x, const PendingContact& y) {
  if (x.softened != y.softened) return !x.softened;
  return deeper(x, y);
}

// Last step's exact points (two triangles' ids) that no exact candidate of this step has:
// the places a cut query did not reach again this step. `deepest`: the deepest of them,
// re-measured at the bodies' poses (0 when none penetrates).
int exactPointsNotFoundAgain(const ContactPoints& points, int candidates,
                             const ContactGroups& groups, btScalar& deepest) {
  int count = 0;
  deepest = 0;
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
      if (found) continue;
      ++count;
      deepest = btMax(deepest, -separationNow(previous, old));
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
  // keeps them, re-measured: this step's new points take the room they leave. Unless this
  // step's deepest exact point is deeper than all of them by more than kSinking breaking
  // thresholds (the body sinks past what they say): then at least half the room is the new
  // points'. Kept points slide with their body (KeptPoints::Slide): with all the room theirs,
  // a gear pressed into a mesh floor under a cut kept points 0.001 apart while it sank
  // through the floor, and the step's 12 exact contacts were all dropped.
  btScalar oldDeepest = 0;
  const int notFound = cut ? exactPointsNotFoundAgain(points, candidates, groups, oldDeepest) : 0;
  const bool sinking =
      !points[0].softened && -points[0].distance > oldDeepest + kSinking * threshold;
  const int keptOld = sinking ? std::min(notFound, capacity / 2) : notFound;
  const int room = capacity - keptOld;
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
