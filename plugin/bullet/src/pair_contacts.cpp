// Contact points of a mesh-mesh pair: exact ones from triangle pairs, plausible ones from
// unresolved node pairs. docs/bullet-budget.md explains the plausible estimate; in short:
//  - normal: the two patches' mean normals, each weighted by how flat its patch is
//    (coherence), A's outward normal and B's inward one averaged; where both patches are
//    curved (the weights cancel) the step's separation hint decides. Mean normals are area
//    integrals over many triangles, so they change little from step to step: stable.
//  - depth: how far B's patch centroid lies behind A's along that normal, clamped to [0, a
//    tenth of the smaller patch's extent along it]: a believed contact is never reported as
//    separated, and a coarse pair's centroids overstate the depth (kPlausibleDepthShare).
//  - point: between the two centroids, so that point on A = point on B + depth * normal.
#include "pair_contacts.h"

#include <BulletCollision/CollisionDispatch/btManifoldResult.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "adb/core/open_pair_estimate.h"
#include "adb/core/triangle_contact.h"
#include "adb/core/triangle_distance.h"
#include "conversions.h"

namespace adb::detail {
namespace {

// Below this length the weighted normal is rounding or cancellation, not a direction.
constexpr double kMinNormalLength = 0.25;
// A plausible contact's depth at most, as a share of the smaller node's extent along the
// normal. The centroids' difference overstates how deep bodies are: on the 50-body pile
// under a quarter of the need the plausible contacts claimed 0.31 to 0.37 while the deepest
// vertex of any body inside another (adb-demo --probe-every) was 0.119 and each body's
// deepest 0.066 on average. At a tenth of the extent they claim 0.06 and bodies go no deeper
// (0.057 on average over 4 seeds; depth 0 gave 0.062 but fewer bodies at rest: a
// plausible contact that cannot push only stops the approach). docs/bullet-results.md.
constexpr double kPlausibleDepthShare = 0.1;
// Bullet's default contact ERP (btContactSolverInfo::m_erp2): a plausible contact with
// probability p corrects p times as much of its depth per step.
constexpr double kDefaultContactErp = 0.8;

Vec3 toWorldPoint(const Pose& pose, const AdbTree& tree, const float local[3]) {
  const Vec3 p(local[0], local[1], local[2]);
  return pose.apply(p + tree.origin());
}

Vec3 toWorldDirection(const Pose& pose, const float local[3]) {
  return pose.rotation * Vec3(local[0], local[1], local[2]);
}

// Half the extent of a node's box along a world direction.
double halfExtentAlong(const Pose& pose, const Node& node, const Vec3& direction) {
  const Vec3 local = pose.rotation.transpose() * direction;
  const Vec3 half = 0.5 * (node.boxHi() - node.boxLo());
  return local.cwiseAbs().dot(half);
}

struct PlausibleContact {
  Vec3 pointOnB;
  Vec3 normal;  // from A towards B
  double depth;
};

PlausibleContact plausibleContact(const PosedPair& pair, const PlausibleChoice& o,
                                  const Vec3& hint) {
  const NodeSurface& sa = pair.a->surfaces()[o.a];
  const NodeSurface& sb = pair.b->surfaces()[o.b];
  const Vec3 ca = toWorldPoint(pair.poseA, *pair.a, sa.centroid);
  const Vec3 cb = toWorldPoint(pair.poseB, *pair.b, sb.centroid);
  // A's outward normal points towards B, B's points towards A: both say "A to B" as na - nb.
  Vec3 n = static_cast<double>(sa.coherence) * toWorldDirection(pair.poseA, sa.normal) -
           static_cast<double>(sb.coherence) * toWorldDirection(pair.poseB, sb.normal);
  double length = n.norm();
  if (!(length > kMinNormalLength)) {
    n = hint;
    length = n.norm();
  }
  if (!(length > 0.0) || !std::isfinite(length)) {
    n = Vec3::UnitY();  // no evidence at all: any unit direction keeps the output finite
    length = 1.0;
  }
  n /= length;
  const double extent = std::min(halfExtentAlong(pair.poseA, pair.a->nodes()[o.a], n),
                                 halfExtentAlong(pair.poseB, pair.b->nodes()[o.b], n));
  const double depth =
      std::clamp((ca - cb).dot(n), 0.0, std::max(0.0, kPlausibleDepthShare * 2.0 * extent));
  const Vec3 middle = 0.5 * (ca + cb);
  return {middle - 0.5 * depth * n, n, depth};
}

// A triangle of a closed mesh faces away from the normal when its outward normal points
// along it by more than this cosine (about 72 degrees from perpendicular): grazing and
// edge-on triangles stay, backs are dropped.
constexpr double kFacingAway = 0.3;

// Whether triangle t (world) of a mesh with `facing` turns its back on `direction`.
bool facesAway(const Vec3 t[3], int facing, const Vec3& direction) {
  if (facing == 0) return false;  // open: two-sided
  const Vec3 n = (t[1] - t[0]).cross(t[2] - t[0]);
  const double length = n.norm();
  if (!(length > 0.0)) return false;  // degenerate: no side to turn
  return static_cast<double>(facing) * n.dot(direction) > kFacingAway * length;
}

// The manifold point btManifoldResult just wrote for `pointOnB`, or nullptr when it refused it
// (beyond the breaking threshold). btManifoldResult does not return its index.
btManifoldPoint* findPoint(btPersistentManifold& manifold, const btVector3& pointOnB) {
  for (int i = 0; i < manifold.getNumContacts(); ++i) {
    btManifoldPoint& p = manifold.getContactPoint(i);
    if (p.m_positionWorldOnB == pointOnB) return &p;
  }
  return nullptr;
}

// A triangle pair within the contact margin: a contact at its closest points, separated by
// their distance (Bullet's solver treats it as speculative: it stops only the approach that
// would close the gap within the step). The normal is the direction between the closest
// points, as Bullet's convex algorithms take it. Returns whether a point was written.
bool addNearContact(const PosedPair& pair, const Vec3 a[3], const Vec3 b[3],
                    ContactPoints& out) {
  const TriangleDistance d = triangleDistance(a[0], a[1], a[2], b[0], b[1], b[2]);
  if (!(d.distance > 0.0) || !std::isfinite(d.distance)) return false;
  const Vec3 normal = (d.pointOnB - d.pointOnA) / d.distance;  // from A towards B
  // As for crossing triangles: A's surface must face B, and B's must face back.
  if (facesAway(a, pair.facingA, -normal) || facesAway(b, pair.facingB, normal)) return false;
  out.push_back({toBt(-normal), toBt(d.pointOnB), static_cast<btScalar>(d.distance)});
  return true;
}

}  // namespace

Vec3 separationHint(const btVector3& lastNormalsOnB, const btVector3& boxCentre0,
                    const btVector3& boxCentre1, bool nested) {
  // Bullet's normal on B points from body 1 towards body 0: the hint is its opposite.
  const Vec3 sum = -fromBt(lastNormalsOnB);
  if (sum.squaredNorm() > 0.0 && sum.allFinite()) return sum;
  // Inside a container (a room, a bowl) the direction between the boxes' centres says
  // nothing: from a room's centre to a body on its floor it points down, through the floor.
  // Nor does the way the body came (tried): a robot sliding along the room's floor, bouncing
  // up a little, had the floor's normal turned down, its contacts refused, and was lost.
  if (nested) return Vec3::Zero();
  return fromBt(boxCentre1 - boxCentre0);
}

namespace {

// Whether a manifold point was made by the same features as `other`.
bool sameFeatures(const btManifoldPoint& point, const btManifoldPoint& other) {
  return point.m_index0 == other.m_index0 && point.m_index1 == other.m_index1 &&
         point.m_partId0 == other.m_partId0 && point.m_partId1 == other.m_partId1 &&
         (point.m_index0 != -1 || point.m_index1 != -1);
}

// The point of last step whose solver state `point` takes over: the one with its features,
// else the nearest unclaimed one within the breaking threshold on body A (Bullet's rule in
// btPersistentManifold::getCacheEntry); -1 for none.
int predecessor(const btManifoldPoint& point, const btManifoldPoint* previous, int count,
                const bool* claimed, btScalar threshold) {
  for (int k = 0; k < count; ++k) {
    if (!claimed[k] && sameFeatures(point, previous[k])) return k;
  }
  int nearest = -1;
  btScalar best = threshold * threshold;
  for (int k = 0; k < count; ++k) {
    if (claimed[k]) continue;
    const btScalar d = (previous[k].m_localPointA - point.m_localPointA).length2();
    if (d < best) {
      best = d;
      nearest = k;
    }
  }
  return nearest;
}

// The unclaimed point of last step made by the same features as `c` (ids as Bullet writes
// them: m_index0 is body 0's), or -1.
int sameFeaturesIn(const PendingContact& c, const btManifoldPoint* previous, int count,
                   const bool* claimed) {
  for (int k = 0; k < count; ++k) {
    if (!claimed[k] && previous[k].m_index0 == c.featureA && previous[k].m_index1 == c.featureB) {
      return k;
    }
  }
  return -1;
}

// What btPersistentManifold::replaceContactPoint keeps of a replaced point: the solver's
// impulses (its warm start) and the point's age.
void inheritSolverState(btManifoldPoint& point, const btManifoldPoint& from) {
  point.m_appliedImpulse = from.m_appliedImpulse;
  point.m_prevRHS = from.m_prevRHS;
  point.m_appliedImpulseLateral1 = from.m_appliedImpulseLateral1;
  point.m_appliedImpulseLateral2 = from.m_appliedImpulseLateral2;
  point.m_lifeTime = from.m_lifeTime;
}

// Whether `point` lies on body A farther than `threshold` from every point the groups hold:
// Bullet would merge it into a nearer one.
bool apartFromAll(const btManifoldPoint& point, const ContactGroups& groups, btScalar threshold) {
  for (int g = 0; g < groups.count; ++g) {
    const btPersistentManifold& manifold = *groups.manifolds[g];
    for (int i = 0; i < manifold.getNumContacts(); ++i) {
      const btVector3 d = manifold.getContactPoint(i).m_localPointA - point.m_localPointA;
      if (d.length2() < threshold * threshold) return false;
    }
  }
  return true;
}

}  // namespace

void writeContactPoints(const ContactPoints& points, btManifoldResult& out,
                        const ContactGroups& groups, int partId0, int partId1,
                        KeptPoints kept) {
  // Last step's points, then empty manifolds: the points written are exactly this step's
  // (Bullet's matching by distance, fed more points than it holds, kept whichever four
  // arrived in a lucky order, and handed one point's impulses to another).
  constexpr int kCapacity = kMaxContactGroups * MANIFOLD_CACHE_SIZE;
  btManifoldPoint previous[kCapacity];
  int count = 0;
  for (int g = 0; g < groups.count; ++g) {
    btPersistentManifold& manifold = *groups.manifolds[g];
    for (int k = 0; k < manifold.getNumContacts(); ++k) {
      previous[count++] = manifold.getContactPoint(k);
    }
    manifold.clearManifold();
  }
  bool claimed[kCapacity] = {};
  const btScalar threshold = groups.manifolds[0]->getContactBreakingThreshold();
  int group = 0;
  out.setPersistentManifold(groups.manifolds[0]);
  for (const PendingContact& c : points) {
    // The next group once this one is full (a speculative point goes to its own manifold).
    while (group + 1 < groups.count &&
           groups.manifolds[group]->getNumContacts() >= MANIFOLD_CACHE_SIZE) {
      out.setPersistentManifold(groups.manifolds[++group]);
    }
    // A plausible point whose node pair last step had too stays as it was made (its anchors
    // and normal; the refresh re-measures it): re-estimated from the open node pairs every
    // step it moved, and its push fed a pile under an eighth of the need ~1 J for good.
    const int frozen = c.softened ? sameFeaturesIn(c, previous, count, claimed) : -1;
    if (frozen >= 0 && c.distance <= threshold) {
      claimed[frozen] = true;
      groups.manifolds[group]->addManifoldPoint(previous[frozen]);
      continue;
    }
    out.setShapeIdentifiersA(partId0, c.featureA);
    out.setShapeIdentifiersB(partId1, c.featureB);
    out.addContactPoint(c.normalOnB, c.pointOnB, c.distance);
    btManifoldPoint* point = findPoint(*groups.manifolds[group], c.pointOnB);
    if (!point) continue;  // refused, or a speculative point (its own manifold)
    const int from = predecessor(*point, previous, count, claimed, threshold);
    if (from >= 0) {
      claimed[from] = true;
      inheritSolverState(*point, previous[from]);
    }
    if (!c.softened) continue;
    point->m_contactERP = c.erp;
    point->m_contactCFM = c.cfm;
    point->m_contactPointFlags |= BT_CONTACT_FLAG_HAS_CONTACT_CFM | BT_CONTACT_FLAG_HAS_CONTACT_ERP;
  }
  // Last step's points that no point of this step's took over stay while there is room and
  // they lie apart from the new ones, as Bullet's persistent manifold keeps them: the
  // refresh below re-measures them at the new poses and drops those now farther than the
  // breaking threshold. Exact contacts come only from crossing triangles: without this, a
  // contact the solver had just pushed apart vanished, the body fell back into it, and the
  // contact came back a step later: a resting body bounced for ever.
  // Exact ones (two triangles' ids) first: a cut query's plausible points left them room.
  for (const bool exact : {true, false}) {
    for (int k = 0; k < count; ++k) {
      const bool isExact = previous[k].m_index0 >= 0 && previous[k].m_index1 >= 0;
      if (claimed[k] || isExact != exact || !apartFromAll(previous[k], groups, threshold)) {
        continue;
      }
      for (int g = 0; g < groups.count; ++g) {
        if (groups.manifolds[g]->getNumContacts() < MANIFOLD_CACHE_SIZE) {
          groups.manifolds[g]->addManifoldPoint(previous[k]);
          break;
        }
      }
    }
  }
  refreshContactGroups(out, groups, kept);
}

namespace {

// A kept point slides along the surface it touches: the point on that surface is moved
// under the point on the other body, in the plane through it normal to the contact, so that
// Bullet's refresh measures the separation there and does not drop the point for having slid.
// The surface is the static body's, or, between two moving bodies, body 1's (the normal is
// Bullet's, on body 1); it is taken as flat about the point until the pair is queried again.
// Why: a pair the budget cut or granted nothing re-measures last step's points, and a body
// jostled in a pile slides a few millimetres a step. Bullet's refresh dropped each point once
// it had slid by the breaking threshold (0.016 in 5 steps), the points between the bodies of a
// six-body pile were gone within 10 steps of a zero budget, and the pile fell through its
// mesh ground; sliding, it stood for 200 steps (docs/bullet-results.md).
void slideAlongSurface(btPersistentManifold& manifold) {
  const btTransform& ta = manifold.getBody0()->getWorldTransform();
  const btTransform& tb = manifold.getBody1()->getWorldTransform();
  const bool surfaceIsA = manifold.getBody0()->isStaticObject();
  for (int i = 0; i < manifold.getNumContacts(); ++i) {
    btManifoldPoint& p = manifold.getContactPoint(i);
    const btVector3& n = p.m_normalWorldOnB;  // on B, towards A
    if (surfaceIsA) {
      const btVector3 onB = tb(p.m_localPointB);
      const btVector3 onA = onB + n * (ta(p.m_localPointA) - onB).dot(n);
      p.m_localPointA = ta.invXform(onA);
    } else {
      const btVector3 onA = ta(p.m_localPointA);
      const btVector3 onB = onA - n * (onA - tb(p.m_localPointB)).dot(n);
      p.m_localPointB = tb.invXform(onB);
    }
  }
}

}  // namespace

btScalar separationNow(const btPersistentManifold& manifold, const btManifoldPoint& point) {
  const btTransform& ta = manifold.getBody0()->getWorldTransform();
  const btTransform& tb = manifold.getBody1()->getWorldTransform();
  return (ta(point.m_localPointA) - tb(point.m_localPointB)).dot(point.m_normalWorldOnB);
}

void refreshContactGroups(btManifoldResult& out, const ContactGroups& groups, KeptPoints kept) {
  for (int g = groups.count - 1; g >= 0; --g) {
    if (kept == KeptPoints::Slide) slideAlongSurface(*groups.manifolds[g]);
    out.setPersistentManifold(groups.manifolds[g]);
    out.refreshContactPoints();
  }
}

namespace {

// Last step's point made by the same two triangles, or nullptr.
const btManifoldPoint* samePoint(const ContactGroups& last, int featureA, int featureB) {
  for (int g = 0; g < last.count; ++g) {
    for (int k = 0; k < last.manifolds[g]->getNumContacts(); ++k) {
      const btManifoldPoint& p = last.manifolds[g]->getContactPoint(k);
      if (p.m_index0 == featureA && p.m_index1 == featureB) return &p;
    }
  }
  return nullptr;
}

// How far triangle b must move along unit n to clear triangle a: max(a.n) - min(b.n).
double depthAlong(const Vec3 a[3], const Vec3 b[3], const Vec3& n) {
  return std::max({n.dot(a[0]), n.dot(a[1]), n.dot(a[2])}) -
         std::min({n.dot(b[0]), n.dot(b[1]), n.dot(b[2])});
}

// A point of last step keeps its normal while the depth along it stays within a breaking
// threshold of the least (contact persistence, as Box2D keeps its reference face within a
// tolerance): the least-depth axis under this step's hint may be another one, nearly as good,
// and a contact that turns its normal between steps shoves a resting body (a ring through a
// tube turned one point's normal by 88 degrees on the second step of a frozen pair). The point
// stays where it was on body 1.
void keepLastNormal(const PosedPair& pair, const Vec3 a[3], const Vec3 b[3],
                    const btManifoldPoint& last, btScalar threshold, TriangleContact& c) {
  const Vec3 n = -fromBt(last.m_normalWorldOnB);  // from A towards B
  if (!n.allFinite() || c.normal.dot(n) > 1.0 - 1e-9) return;
  const double depth = depthAlong(a, b, n);
  if (!(depth >= 0.0 && depth <= c.depth + static_cast<double>(threshold))) return;
  c.normal = n;
  c.depth = depth;
  c.pointOnB = pair.poseB.apply(fromBt(last.m_localPointB));
}

}  // namespace

std::uint32_t addExactContacts(const PosedPair& pair, const std::vector<Witness>& witnesses,
                               const Vec3& hint, const ContactGroups& last, ContactPoints& out) {
  std::uint32_t written = 0;
  const btScalar threshold =
      last.count > 0 ? last.manifolds[0]->getContactBreakingThreshold() : btScalar(0);
  for (const Witness& w : witnesses) {
    if (!w.isExact()) continue;
    Vec3 a[3], b[3];
    worldTriangle(*pair.a, pair.poseA, w.triangleA, a);
    worldTriangle(*pair.b, pair.poseB, w.triangleB, b);
    if (w.distance > 0.0f) {
      if (addNearContact(pair, a, b, out)) {
        out.back().featureA = static_cast<int>(pair.a->meshTriangle(w.triangleA));
        out.back().featureB = static_cast<int>(pair.b->meshTriangle(w.triangleB));
        ++written;
      }
      continue;
    }
    TriangleContact c = triangleContact(a[0], a[1], a[2], b[0], b[1], b[2], hint);
    if (!c.valid) continue;
    const int featureA = static_cast<int>(pair.a->meshTriangle(w.triangleA));
    const int featureB = static_cast<int>(pair.b->meshTriangle(w.triangleB));
    if (const btManifoldPoint* previous = samePoint(last, featureA, featureB)) {
      keepLastNormal(pair, a, b, *previous, threshold, c);
    }
    // B is pushed along +normal: A's surface must face it, B's must face back.
    if (facesAway(a, pair.facingA, -c.normal) || facesAway(b, pair.facingB, c.normal)) continue;
    // Bullet: the normal on B points from body 1 towards body 0, the point lies on body 1,
    // and a negative distance is a penetration.
    PendingContact point{toBt(-c.normal), toBt(c.pointOnB), static_cast<btScalar>(-c.depth)};
    point.featureA = featureA;
    point.featureB = featureB;
    out.push_back(point);
    ++written;
  }
  return written;
}

int selectPlausible(const AdbTree& a, const AdbTree& b, const std::vector<OpenPair>& open,
                    const FrameSettings& settings, PlausibleChoices& chosen) {
  // The most probable pairs, kept sorted in a fixed buffer: no allocation per step. Each
  // pair's probability is worked out once: the estimate reads both nodes' statistics.
  const int limit = std::clamp(settings.maxPlausibleContacts, 0, kMaxPlausibleContacts);
  int count = 0;
  for (const OpenPair& o : open) {
    // The roots' pair is the whole of both meshes: too coarse to place a contact.
    if (o.a == 0 && o.b == 0) continue;
    if (limit == 0) break;
    const double p = openPairProbability(o, a, b);
    if (!(p >= settings.pAccept)) continue;
    // Ties keep the order of `open`: the same contacts step after step for the same query.
    if (count == limit && p <= chosen[count - 1].probability) continue;
    int i = count < limit ? count++ : count - 1;
    for (; i > 0 && chosen[i - 1].probability < p; --i) chosen[i] = chosen[i - 1];
    chosen[i] = PlausibleChoice{o.a, o.b, p};
  }
  return count;
}

std::uint32_t addPlausibleContacts(const PosedPair& pair, const std::vector<OpenPair>& open,
                                   const FrameSettings& settings, const Vec3& hint,
                                   ContactPoints& out) {
  PlausibleChoices best;
  const int count = selectPlausible(*pair.a, *pair.b, open, settings, best);
  const double certain = 1.0 - settings.pAccept;
  for (int i = 0; i < count; ++i) {
    const PlausibleContact c = plausibleContact(pair, best[i], hint);
    PendingContact point{toBt(-c.normal), toBt(c.pointOnB), static_cast<btScalar>(-c.depth)};
    point.featureA = plausibleFeature(best[i].a);
    point.featureB = plausibleFeature(best[i].b);
    if (settings.softenPlausible) {
      const double p = best[i].probability;  // in [0, 1] (openPairProbability)
      point.softened = true;
      point.erp = static_cast<btScalar>(kDefaultContactErp * p);
      // (1 - p) / (1 - pAccept) runs from 1 at the threshold to 0 when certain; guarded for
      // pAccept = 1, where only p = 1 is accepted and nothing is softened.
      point.cfm =
          static_cast<btScalar>(certain > 0.0 ? settings.softCfm * (1.0 - p) / certain : 0.0);
    }
    out.push_back(point);
  }
  return static_cast<std::uint32_t>(count);
}

}  // namespace adb::detail
