// The one call that registers adb's collision algorithms with a Bullet dispatcher, and the
// algorithm pool size they need.
//
// A MeshShape meets every shape type Bullet has: registration covers mesh-mesh, mesh
// against every convex type, mesh against a static plane and mesh against every other
// concave type, in both orders, for contacts and for closest points. Under adb::Dispatcher
// every one of those pairs runs within the step's budget (adb/bullet/frame_budget.h); with
// a plain btCollisionDispatcher each is answered at once, exactly.
#pragma once

#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>

#include <cstddef>

#include "adb/bullet/precision.h"

namespace adb {

/// Bytes a dispatcher's algorithm pool must hold per element for adb's algorithms: pass it
/// as btDefaultCollisionConstructionInfo::m_customCollisionAlgorithmMaxElementSize.
std::size_t algorithmPoolElementSize();

/// Bullet's construction info with the algorithm pool sized for adb: start a world's
/// btDefaultCollisionConfiguration from this (and change what else it needs).
btDefaultCollisionConstructionInfo collisionConstructionInfo();

/// Registers adb's algorithms on `dispatcher`. Throws SettingsError when `configuration`'s
/// algorithm pool holds fewer than algorithmPoolElementSize() bytes per element (Bullet's
/// release build would overrun it).
void registerAlgorithms(btCollisionDispatcher& dispatcher,
                        btDefaultCollisionConfiguration& configuration);

}  // namespace adb
