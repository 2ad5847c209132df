// Internal: contact points of a mesh-mesh pair from a query's evidence, written into Bullet's
// manifold. Exact contacts come from intersecting triangle pairs (triangleContact); plausible
// ones from node pairs a budget left unresolved (their surface statistics).
#pragma once

#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <cstdint>
#include <vector>

#include "adb/bullet/frame_budget.h"
#include "adb/core/query.h"
#include "adb/core/tree.h"

class btManifoldResult;

namespace adb::detail {

/// Two posed trees: body 0's and body 1's, with the way their triangles face (MeshData).
struct PosedPair {
  const AdbTree* a;
  Pose poseA;
  const AdbTree* b;
  Pose poseB;
  int facingA = 0, facingB = 0;
};

/// The preferred separation direction from body 0 towards body 1 for this step: the last
/// step's contact normals when the manifold has points (warm starting: resting contact keeps
/// its normal), else the direction between the two world boxes' centres.
Vec3 separationHint(const btPersistentManifold* manifold, const btVector3& boxCentre0,
                    const btVector3& boxCentre1);

/// One contact per intersecting triangle pair among `witnesses` (node-only witnesses are
/// skipped), except where a triangle of a closed mesh faces away from the contact normal:
/// such a pair is not two surfaces meeting (coplanar side faces of stacked boxes, the far
/// wall of a penetrated tube) and pushing along it shoves bodies sideways. Returns the
/// number of points written.
std::uint32_t addExactContacts(const PosedPair& pair, const std::vector<Witness>& witnesses,
                               const Vec3& hint, btManifoldResult& out);

/// Plausible contacts from the unresolved node pairs with probability >= settings.pAccept
/// (the most probable first, at most settings.maxPlausibleContacts), softened by their
/// probability when settings.softenPlausible. Returns the number of points written.
std::uint32_t addPlausibleContacts(const PosedPair& pair, const std::vector<OpenPair>& open,
                                   const FrameSettings& settings, const Vec3& hint,
                                   btManifoldResult& out, btPersistentManifold& manifold);

/// Contacts a pair may get from plausible evidence at most: a bound for the fixed-size
/// selection buffer (no allocation per step).
constexpr int kMaxPlausibleContacts = 32;

}  // namespace adb::detail
