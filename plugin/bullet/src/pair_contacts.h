// Internal: contact points of a mesh-mesh pair from a query's evidence, computed on any
// thread into a pair's ContactPoints, then written into Bullet's manifold on the stepping
// thread. Exact contacts come from intersecting triangle pairs (triangleContact); plausible
// ones from node pairs a budget left unresolved (their surface statistics).
#pragma once

#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <array>
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

/// A contact point as Bullet takes it: the normal on body 1 points towards body 0, the point
/// lies on body 1, and a negative distance is a penetration. A softened (plausible) point
/// carries its own ERP and CFM.
///
/// Its identity: the features of body 0 and body 1 that made it, written to the manifold
/// point's m_index0 and m_index1 (Bullet's triangle index), so that the same point is known
/// again next step. An exact point's are its two triangles (>= 0, the meshes' own indices); a plausible point's are
/// its two tree nodes as plausibleFeature(node) (<= -2: no triangle); -1 is none.
struct PendingContact {
  btVector3 normalOnB;
  btVector3 pointOnB;
  btScalar distance = 0;
  bool softened = false;
  btScalar erp = 0, cfm = 0;
  int featureA = -1, featureB = -1;
};

/// A tree node as a contact's feature: negative, below Bullet's -1 (none), so that it is
/// never taken for a triangle index.
constexpr int plausibleFeature(std::uint32_t node) { return -2 - static_cast<int>(node); }

/// One pair's contact points of a step, in the order they are written (reused: it grows to
/// the pair's most points, then stays).
using ContactPoints = std::vector<PendingContact>;

/// Most manifolds one pair's contacts are written to.
constexpr int kMaxContactGroups = 2;

/// The manifolds a pair's contact points go to, in order, each holding Bullet's 4: the pair's
/// manifold and, for a mesh-mesh pair without speculative contacts this step, its second
/// (ManifoldAlgorithm::secondGroupManifold). Why two: a body held at 4 points rocks. Piled
/// meshes rest on several regions of each other (gear teeth, a ring on two strands, a tube's
/// rim inside another); at 4 points a pair held one or two of them, the solver's push on
/// those spun the body over 1 rad/s, and piles stayed awake; at 8 they settle
/// (docs/bullet-results.md, "Piles that fall asleep"; 12 settled no better).
struct ContactGroups {
  btPersistentManifold* manifolds[kMaxContactGroups] = {};
  int count = 0;
};

/// A manifold point's separation re-measured at its bodies' current poses (what Bullet's
/// refresh would give it; < 0 penetrating).
btScalar separationNow(const btPersistentManifold& manifold, const btManifoldPoint& point);

/// How last step's points, kept, are re-measured.
enum class KeptPoints {
  /// As Bullet does: dropped once they slid along the surface by the breaking threshold.
  Drop,
  /// Slid along the surface they touch (the static body's, else body 1's): the point on it
  /// is moved under the other body's point, in the plane of the contact.
  Slide,
};

/// Re-measures every group's points at the bodies' poses (Bullet's refreshContactPoints,
/// through `out`, whose manifold it leaves on the first group); with KeptPoints::Slide, the
/// points slide along their surface first.
void refreshContactGroups(btManifoldResult& out, const ContactGroups& groups,
                          KeptPoints kept = KeptPoints::Drop);

/// Writes `points` through `out` (btManifoldResult or a SpeculativeResult) in place of what
/// the `groups` held, in order, each with its features and the wrappers' part ids
/// (`partId0`, `partId1`), filling each group's manifold before the next, and sets the
/// softened ones' ERP and CFM. A point whose features a point of last step had (in any
/// group) takes over that point's solver state (its impulses, warm-starting the solver, and
/// its age); one without takes it from the nearest unclaimed point within the breaking
/// threshold, as Bullet's own matching would. Then refreshes every group for the bodies'
/// poses (`kept`: how last step's points kept are re-measured) and leaves `out` on the
/// first. The stepping thread's part.
void writeContactPoints(const ContactPoints& points, btManifoldResult& out,
                        const ContactGroups& groups, int partId0, int partId1,
                        KeptPoints kept = KeptPoints::Drop);

/// The preferred separation direction from body 0 towards body 1 for this step: against the
/// last step's contact normals on body 1 (`lastNormalsOnB`, their sum; warm starting:
/// resting contact keeps its normal), else, without them, the direction between the two
/// world boxes' centres, unless one box holds the other's centre (`nested`): then none.
Vec3 separationHint(const btVector3& lastNormalsOnB, const btVector3& boxCentre0,
                    const btVector3& boxCentre1, bool nested);

/// One contact per intersecting triangle pair among `witnesses` (node-only witnesses are
/// skipped), except where a triangle of a closed mesh faces away from the contact normal:
/// such a pair is not two surfaces meeting (coplanar side faces of stacked boxes, the far
/// wall of a penetrated tube) and pushing along it shoves bodies sideways. A triangle pair
/// that made one of the points of `resting` (last step's, for a pair at rest; empty
/// otherwise) keeps that point's normal and place on body 1 while the depth along it stays
/// within a breaking threshold of the least. Returns the number of points added to `out`.
std::uint32_t addExactContacts(const PosedPair& pair, const std::vector<Witness>& witnesses,
                               const Vec3& hint, const ContactGroups& resting,
                               ContactPoints& out);

/// Contacts a pair may get from plausible evidence at most: a bound for the fixed-size
/// selection buffer (no allocation per step).
constexpr int kMaxPlausibleContacts = 32;

/// An unresolved node pair chosen to become a plausible contact, with its probability.
struct PlausibleChoice {
  std::uint32_t a = 0, b = 0;  ///< node indices in tree A and tree B
  double probability = 0.0;    ///< openPairProbability (adb/core/open_pair_estimate.h)
};
using PlausibleChoices = std::array<PlausibleChoice, kMaxPlausibleContacts>;

/// The unresolved node pairs `open` of a query between trees `a` and `b` that become
/// plausible contacts, into `chosen`: those whose calibrated probability that a triangle
/// below one node meets one below the other (openPairProbability, worked out once per open
/// pair) is >= settings.pAccept, the most probable first (ties in the order of `open`), at
/// most settings.maxPlausibleContacts, never the roots' pair. Returns how many. A function
/// of its arguments only: the contact audit (contact_audit.h) calls it again to know which
/// open pairs were accepted.
int selectPlausible(const AdbTree& a, const AdbTree& b, const std::vector<OpenPair>& open,
                    const FrameSettings& settings, PlausibleChoices& chosen);

/// Plausible contacts from the open pairs selectPlausible chooses, softened by their
/// probability when settings.softenPlausible. Returns the number of points added to `out`.
std::uint32_t addPlausibleContacts(const PosedPair& pair, const std::vector<OpenPair>& open,
                                   const FrameSettings& settings, const Vec3& hint,
                                   ContactPoints& out);

}  // namespace adb::detail
