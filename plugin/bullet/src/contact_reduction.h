// Internal: a mesh-mesh pair's contact points reduced to the few its manifold holds, by a rule
// that gives the same points for the same contact every step.
//
// A pair of piled meshes crosses in up to 64 triangle pairs a step (and a cut pair adds up to
// 32 plausible points); Bullet's manifold holds 4. Fed them one by one in traversal order, it
// kept whichever four arrived in a lucky order, and which four changed from step to step:
// resting bodies jittered and piles stayed awake (docs/bullet-results.md, "Piles that fall
// asleep"). Here the choice depends only on the points themselves and on last step's:
//  1. the deepest point (ties: by features), which stops the bodies sinking;
//  2. the points whose features (PendingContact::featureA/B) last step's manifolds held, in
//     their order: a contact that is still there stays, and keeps its impulses;
//  3. then greedily the point farthest from those chosen: the widest support, which also
//     reaches a second region of contact (a ring hooked over another touches it twice).
// Chosen points lie farther apart than the breaking threshold on body A: Bullet merges a new
// point into a kept one closer than that. Points beyond the threshold (speculative ones, for
// their own manifold) are not reduced. No allocation: the points are reordered in place.
#pragma once

#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include "pair_contacts.h"

namespace adb::detail {

/// Points a mesh-mesh pair writes to each of its manifolds at most: the 4 one holds (a fifth
/// would make it drop one of the others every step).
constexpr int kManifoldPoints = 4;

/// Reorders `points` so that the ones chosen for the pair's `groups` (their manifolds before
/// this step's points; kManifoldPoints for each group) come first in the order they were
/// chosen, followed by the speculative ones, and drops the rest. Exact points go before
/// plausible ones. After a `cut` query, last step's points come first, and this step's new
/// points take only the room left by last step's exact points the query did not reach
/// again (the writer keeps those, re-measured): a cut never deletes a contact that held a
/// body, and a cut pair at rest writes the same points every step.
void reduceContacts(ContactPoints& points, const ContactGroups& groups, bool cut = false);

}  // namespace adb::detail
