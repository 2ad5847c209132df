// Internal: what a step left in the world, read after it: contact points with their pairs'
// confidence, the pairs a budget cut, and the dynamic bodies' energy and rest.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <vector>

#include "adb/bullet/dispatcher.h"
#include "adb/scene/scene_world.h"

namespace adb::scene::detail {

/// Contact points from every manifold of `dispatcher` (bodies named by their user index),
/// coloured by their pair's confidence when `adb` (the same dispatcher, when it is adb's)
/// reports the pair; `reports` is reused memory. Fills the record's contact and pair figures.
void measureContacts(const btCollisionDispatcher& dispatcher, const Dispatcher* adb,
                     std::vector<MeshPairReport>& reports, StepRecord& record,
                     std::vector<ContactPoint>& contacts, std::vector<CutPair>& cutPairs);

/// Kinetic and potential energy (gravity `gravity`) of the world's dynamic bodies, and how
/// many are at rest.
void measureDynamics(const btDiscreteDynamicsWorld& world, const Vec3& gravity,
                     StepRecord& record);

}  // namespace adb::scene::detail
