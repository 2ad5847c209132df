// MeshMeshAlgorithm: a MeshShape pair, deferred to the step's scheduler or answered at once.
#include "mesh_mesh_algorithm.h"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>

#include <algorithm>
#include <string>

#include "adb/bullet/mesh_shape.h"
#include "contact_reduction.h"
#include "conversions.h"
#include "frame_scheduler.h"
#include "near_face_corners.h"
#include "pair_contacts.h"
#include "speculative_result.h"

namespace adb {
namespace {


// Triangle pairs turned into contacts per pair and step at most: the candidates from which
// reduceContacts picks the manifold's 4; more would cost without changing the choice much.
constexpr std::uint32_t kMaxContactPairs = 64;

// Contact sampling: at most 4 intersecting triangle pairs per region of the overlap (a node
// pair whose depths add up to 8: about a sixteenth of each mesh) instead of all of them.
// Piled meshes intersect in up to thousands of triangle pairs, and enumerating them was 90 %
// of the 50-body pile's collision time, for the 4 points a manifold keeps. Measured on that
// pile (docs/bullet-results.md): regions at depth 6 are 25 % faster but let bodies sink
// 40 % deeper; 8 hits per region cost 25 % more for no gain.
constexpr std::uint32_t kHitsPerRegion = 4;
constexpr int kRegionDepth = 8;

// Contacts between meshes come from crossing triangles, and, for a fast body that asks for
// continuous collision detection, from triangle pairs within the distance the bodies can close
// in the step (speculativeReach, QuerySettings::contactMargin). A margin at Bullet's breaking
// threshold for every pair was tried: on the gallery pile it cost 4.5x the time (the node
// pairs within 0.011 of each other, not only the crossing ones) and the pile no longer came
// to rest (22 of 30 bodies at 1,200 steps, against all 30 from step 600 without it;
// docs/bullet-budget.md has the commands).
QuerySettings forContacts(QuerySettings s, double margin) {
  s.stopAtFirstHit = false;
  s.maxWitnesses = kMaxContactPairs;
  s.hitsPerRegion = kHitsPerRegion;
  s.regionDepth = kRegionDepth;
  // Contacts come from the witnesses: once they are full, every further hit would be
  // dropped, and the rest of the descent would change nothing but its own cost.
  s.stopWhenWitnessesFull = true;
  if (margin > 0.0) {
    // Speculative contacts must be the closest pairs (the witnesses keep the closest once
    // full), not the first the descent finds: sampled per region in the trees' order, a gear
    // at 30 m/s got contacts 0.38 to 0.5 apart, with slanted normals, where the wall was 0.3
    // away, and went through it.
    s.contactMargin = margin;
    s.hitsPerRegion = 0;
    s.stopWhenWitnessesFull = false;
  }
  return s;
}

const MeshShape& meshOf(const btCollisionObjectWrapper* body) {
  return *static_cast<const MeshShape*>(body->getCollisionShape());
}

// A fast pair's speculative contacts, made conservative: the closest near pair's distance
// and normal at the four corners of the smaller body's root box that face the other body.
// Why: the near pairs kept are the 64 closest, and a face falling flat onto a face has
// hundreds at one distance: the 64 kept lay in one corner of the gear, the solver stopped
// that corner only, and the gear turned about it through a 4 cm mesh slab at 50 m/s. With
// the closest distance at the corners, no point of the body closes more than that in the
// step (the bodies meet no sooner than there); the next step measures again from nearer.
void spreadSpeculativeContacts(const MeshShape& mesh0, const btTransform& transform0,
                               const MeshShape& mesh1, const btTransform& transform1,
                               btScalar threshold, detail::ContactPoints& points) {
  const detail::PendingContact* closest = nullptr;
  for (const detail::PendingContact& c : points) {
    if (!closest || c.distance < closest->distance) closest = &c;
  }
  if (!closest) return;
  detail::PendingContact nearest = *closest;
  const auto speculative = [&](const detail::PendingContact& c) { return c.distance > threshold; };
  points.erase(std::remove_if(points.begin(), points.end(), speculative), points.end());
  // Speculative points only (their own manifold): once the bodies touch, the corners may
  // close by the breaking threshold, and the touching points (the pair's manifold) hold.
  nearest.distance = btMax(nearest.distance, threshold * btScalar(1.001));
  nearest.softened = false;
  const auto rootSize = [](const MeshShape& m) {
    const Node& root = m.tree().root();
    return (root.boxHi() - root.boxLo()).squaredNorm();
  };
  // Corners of body 1 (B) face A along +normal; body 0's (A) face B along -normal.
  const bool onB = rootSize(mesh1) <= rootSize(mesh0);
  const MeshShape& mesh = onB ? mesh1 : mesh0;
  const btTransform& pose = onB ? transform1 : transform0;
  const btVector3 towardsOther = onB ? nearest.normalOnB : -nearest.normalOnB;
  for (const btVector3& corner : detail::nearFaceCorners(mesh, pose, towardsOther)) {
    detail::PendingContact c = nearest;
    c.pointOnB = onB ? corner : corner - nearest.normalOnB * nearest.distance;
    c.featureA = c.featureB = -1;
    points.push_back(c);
  }
}

struct WorldBox {
  btVector3 lo, hi;
  btVector3 centre() const { return 0.5 * (lo + hi); }
  // Whether this box is a container of `other`: it holds other's centre and is at least
  // twice as large across (two bodies of a pile overlap their boxes all the time).
  bool contains(const WorldBox& other) const {
    const btVector3 p = other.centre();
    const bool holds = lo.x() <= p.x() && p.x() <= hi.x() && lo.y() <= p.y() &&
                       p.y() <= hi.y() && lo.z() <= p.z() && p.z() <= hi.z();
    const btVector3 size = hi - lo, otherSize = other.hi - other.lo;
    return holds && size[size.maxAxis()] >= 2 * otherSize[otherSize.maxAxis()];
  }
};

WorldBox worldBox(const btCollisionShape* shape, const btTransform& transform) {
  WorldBox b;
  shape->getAabb(transform, b.lo, b.hi);
  return b;
}

}  // namespace

std::uint64_t MeshMeshAlgorithm::collideNow(const btCollisionObjectWrapper* body0,
                                           const btCollisionObjectWrapper* body1,
                                           const btDispatcherInfo&, btManifoldResult* result) {
  QuerySettings settings;
  settings.mode = QueryMode::Exact;
  if (!start(meshOf(body0).tree(), body0->getWorldTransform(), meshOf(body1).tree(),
             body1->getWorldTransform(), forContacts(settings, contactMargin()))) {
    return 0;
  }
  const QueryResult& r = m_traversal.step();
  m_lastStop = r.stop;
  computePoints(body0->getCollisionShape(), body0->getWorldTransform(),
                body1->getCollisionShape(), body1->getWorldTransform(), FrameSettings{});
  writePoints(body0, body1, *result);
  return r.nodePairs + r.triangleTests;
}

const QueryResult& MeshMeshAlgorithm::query(const detail::DeferredPair& pair,
                                            const QuerySettings& settings,
                                            const StepBudget& budget, bool resume) {
  if (!resume) {
    const auto& shape0 = *static_cast<const MeshShape*>(pair.shape0);
    const auto& shape1 = *static_cast<const MeshShape*>(pair.shape1);
    start(shape0.tree(), pair.transform0, shape1.tree(), pair.transform1,
          forContacts(settings, contactMargin()));
  }
  const QueryResult& r = m_traversal.step(budget);
  m_lastStop = r.stop;
  m_pointsReady = false;
  // The result's counters cover every step of this query: what the pair used this frame.
  m_neededFromScratch = r.fromScratchNodePairs;
  if (!isBudgetStop(r.stop)) {
    m_needed = r.nodePairs;
  } else {
    // Cut: it needs more than it had. Without this a pair first met while barely touching
    // would be granted its old need step after step while the bodies sink into each other.
    m_needed = std::max(m_needed, 2 * r.nodePairs);
  }
  return r;
}

double MeshMeshAlgorithm::contactMargin() const {
  // Near pairs within Bullet's threshold too, once there is a gap to speculate over.
  return speculativeReach() > 0 ? static_cast<double>(contactReach()) : 0.0;
}

bool MeshMeshAlgorithm::start(const AdbTree& tree0, const btTransform& transform0,
                              const AdbTree& tree1, const btTransform& transform1,
                              const QuerySettings& settings) {
  try {
    m_traversal.reset(tree0, toPose(transform0), tree1, toPose(transform1), settings);
    return true;
  } catch (const PoseError&) {
    // processCollision checked both poses (acceptPoses); kept as the last guard, since no
    // exception may leave Bullet's step: the pair gets no contacts (an empty, finished
    // traversal).
    m_traversal = Traversal();
    m_lastStop = StopReason::Completed;
    return false;
  }
}

void MeshMeshAlgorithm::computeContacts(const detail::DeferredPair& pair,
                                        const FrameSettings& settings) {
  computePoints(pair.shape0, pair.transform0, pair.shape1, pair.transform1, settings);
}

ContactCount MeshMeshAlgorithm::writeContacts(const detail::DeferredPair& pair,
                                              const FrameSettings& settings) {
  if (!m_pointsReady) computeContacts(pair, settings);
  const detail::PairWrappers wrappers(pair);
  detail::SpeculativeResult result(&wrappers.body0, &wrappers.body1, speculativeManifold(),
                                   contactReach());
  return writePoints(&wrappers.body0, &wrappers.body1, result);
}

void MeshMeshAlgorithm::computePoints(const btCollisionShape* shape0,
                                      const btTransform& transform0,
                                      const btCollisionShape* shape1,
                                      const btTransform& transform1,
                                      const FrameSettings& settings) {
  const auto& mesh0 = *static_cast<const MeshShape*>(shape0);
  const auto& mesh1 = *static_cast<const MeshShape*>(shape1);
  const detail::PosedPair posed{&mesh0.tree(), toPose(transform0), &mesh1.tree(),
                                toPose(transform1), mesh0.data().facing, mesh1.data().facing};
  // The manifold was made when Bullet dispatched the pair, and only this pair writes it: read
  // here, on whichever thread, before this step's points are written.
  const WorldBox box0 = worldBox(shape0, transform0), box1 = worldBox(shape1, transform1);
  const bool nested = box0.contains(box1) || box1.contains(box0);
  const Vec3 hint =
      detail::separationHint(lastNormalsOnB(), box0.centre(), box1.centre(), nested);
  m_points.clear();
  m_pointCount = ContactCount{};
  // A pair at rest keeps its points' normals (addExactContacts); one in motion takes each
  // pair of triangles' least depth afresh.
  const detail::ContactGroups resting =
      barelyMoved(motionSinceLastRun(transform0, transform1)) ? contactGroups()
                                                               : detail::ContactGroups{};
  m_pointCount.exact =
      detail::addExactContacts(posed, m_traversal.witnesses(), hint, resting, m_points);
  if (speculativeReach() > 0) {
    spreadSpeculativeContacts(mesh0, transform0, mesh1, transform1, breakingThreshold(),
                              m_points);
  }
  if (isBudgetStop(m_lastStop) || m_lastStop == StopReason::QualityReached) {
    m_pointCount.plausible = detail::addPlausibleContacts(posed, m_traversal.openPairs(),
                                                          settings, hint, m_points);
  }
  const detail::ContactGroups groups = contactGroups();
  if (groups.count > 0) detail::reduceContacts(m_points, groups, isBudgetStop(m_lastStop));
  m_pointsReady = true;
}

ContactCount MeshMeshAlgorithm::writePoints(const btCollisionObjectWrapper* body0,
                                            const btCollisionObjectWrapper* body1,
                                            btManifoldResult& result) {
  manifoldFor(body0, body1, &result);
  // A cut pair's points of last step that it did not find again are kept, slid along their
  // surface as a pair granted nothing keeps its points (keepLastContacts).
  detail::writeContactPoints(m_points, result, contactGroups(), body0->m_partId,
                             body1->m_partId,
                             cut() ? detail::KeptPoints::Slide : detail::KeptPoints::Drop);
  m_pointsReady = false;
  return m_pointCount;
}

}  // namespace adb
