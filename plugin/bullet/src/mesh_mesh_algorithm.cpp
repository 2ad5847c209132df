// MeshMeshAlgorithm: a MeshShape pair, deferred to the step's scheduler or answered at once.
#include "adb/bullet/mesh_mesh_algorithm.h"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <LinearMath/btPoolAllocator.h>

#include <algorithm>
#include <string>

#include "adb/bullet/dispatcher.h"
#include "adb/bullet/mesh_concave_algorithm.h"
#include "adb/bullet/mesh_convex_algorithm.h"
#include "adb/bullet/mesh_plane_algorithm.h"
#include "adb/bullet/mesh_shape.h"
#include "conversions.h"
#include "frame_scheduler.h"
#include "pair_contacts.h"

namespace adb {
namespace {

using detail::toPose;

// Triangle pairs turned into contacts per pair and step at most: the manifold keeps 4 points
// (Bullet's reduction picks the widest), so more would cost without changing the result much.
constexpr std::uint32_t kMaxContactPairs = 64;

// Contact sampling: at most 4 intersecting triangle pairs per region of the overlap (a node
// pair whose depths add up to 8: about a sixteenth of each mesh) instead of all of them.
// Piled meshes intersect in up to thousands of triangle pairs, and enumerating them was 90 %
// of the 50-body pile's collision time, for the 4 points a manifold keeps. Measured on that
// pile (docs/bullet-results.md): regions at depth 6 are 25 % faster but let bodies sink
// 40 % deeper; 8 hits per region cost 25 % more for no gain.
constexpr std::uint32_t kHitsPerRegion = 4;
constexpr int kRegionDepth = 8;

QuerySettings forContacts(QuerySettings s) {
  s.stopAtFirstHit = false;
  s.maxWitnesses = kMaxContactPairs;
  s.hitsPerRegion = kHitsPerRegion;
  s.regionDepth = kRegionDepth;
  return s;
}

const MeshShape& meshOf(const btCollisionObjectWrapper* body) {
  return *static_cast<const MeshShape*>(body->getCollisionShape());
}

btVector3 boxCentre(const btCollisionObjectWrapper* body) {
  btVector3 lo, hi;
  body->getCollisionShape()->getAabb(body->getWorldTransform(), lo, hi);
  return 0.5 * (lo + hi);
}

}  // namespace

MeshMeshAlgorithm::MeshMeshAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
                                     const btCollisionObjectWrapper* body0,
                                     const btCollisionObjectWrapper* body1, bool swapped)
    : ManifoldAlgorithm(ci, body0, body1, swapped) {
  // Looked up once per pair, not per step.
  if (auto* dispatcher = dynamic_cast<Dispatcher*>(ci.m_dispatcher1)) {
    m_scheduler = &dispatcher->scheduler();
  }
}

void MeshMeshAlgorithm::processCollision(const btCollisionObjectWrapper* body0,
                                         const btCollisionObjectWrapper* body1,
                                         const btDispatcherInfo&, btManifoldResult* result) {
  // Only top-level pairs of a world's dispatch can wait for the scheduler: a compound's
  // child wrappers, and contactTest's callbacks, live only during this call.
  if (!acceptPoses(body0, body1)) return;
  const bool topLevel = !body0->m_parent && !body1->m_parent;
  if (m_scheduler && m_scheduler->collecting() && topLevel) {
    m_scheduler->defer(detail::DeferredPair{
        this, body0->getCollisionObject(), body1->getCollisionObject(),
        body0->getWorldTransform(), body1->getWorldTransform(), body0->m_partId,
        body0->m_index, body1->m_partId, body1->m_index, 0, 0.0, StopReason::Completed, false});
    return;
  }
  QuerySettings settings;
  settings.mode = QueryMode::Exact;
  if (!start(meshOf(body0).tree(), body0->getWorldTransform(), meshOf(body1).tree(),
             body1->getWorldTransform(), forContacts(settings))) {
    return;
  }
  m_lastStop = m_traversal.step().stop;
  addContacts(body0, body1, *result, FrameSettings{});
}

const QueryResult& MeshMeshAlgorithm::query(const detail::DeferredPair& pair,
                                            const QuerySettings& settings,
                                            const StepBudget& budget, bool resume) {
  if (!resume) {
    const auto& shape0 = *static_cast<const MeshShape*>(pair.object0->getCollisionShape());
    const auto& shape1 = *static_cast<const MeshShape*>(pair.object1->getCollisionShape());
    start(shape0.tree(), pair.transform0, shape1.tree(), pair.transform1, forContacts(settings));
  }
  const QueryResult& r = m_traversal.step(budget);
  m_lastStop = r.stop;
  // The result's counters cover every step of this query: what the pair used this frame.
  if (r.stop == StopReason::Completed || r.stop == StopReason::QualityReached) {
    m_needed = r.nodePairs;
  } else {
    // Cut: it needs more than it had. Without this a pair first met while barely touching
    // would be granted its old need step after step while the bodies sink into each other.
    m_needed = std::max(m_needed, 2 * r.nodePairs);
  }
  return r;
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

ContactCount MeshMeshAlgorithm::writeContacts(const detail::DeferredPair& pair,
                                              const FrameSettings& settings) {
  // Bullet's wrappers and result, rebuilt as the dispatch made them for this pair.
  const btCollisionObjectWrapper body0(nullptr, pair.object0->getCollisionShape(), pair.object0,
                                       pair.transform0, pair.partId0, pair.index0);
  const btCollisionObjectWrapper body1(nullptr, pair.object1->getCollisionShape(), pair.object1,
                                       pair.transform1, pair.partId1, pair.index1);
  btManifoldResult result(&body0, &body1);
  return addContacts(&body0, &body1, result, settings);
}

ContactCount MeshMeshAlgorithm::addContacts(const btCollisionObjectWrapper* body0,
                                            const btCollisionObjectWrapper* body1,
                                            btManifoldResult& result,
                                            const FrameSettings& settings) {
  btPersistentManifold* manifold = manifoldFor(body0, body1, &result);
  const MeshShape& shape0 = meshOf(body0);
  const MeshShape& shape1 = meshOf(body1);
  const detail::PosedPair posed{&shape0.tree(), toPose(body0->getWorldTransform()),
                                &shape1.tree(), toPose(body1->getWorldTransform()),
                                shape0.data().facing, shape1.data().facing};
  const Vec3 hint = detail::separationHint(manifold, boxCentre(body0), boxCentre(body1));
  ContactCount count;
  count.exact = detail::addExactContacts(posed, m_traversal.witnesses(), hint, result);
  if (m_lastStop != StopReason::Completed) {
    count.plausible = detail::addPlausibleContacts(posed, m_traversal.openPairs(), settings,
                                                   hint, result, *manifold);
  }
  result.refreshContactPoints();
  return count;
}

std::size_t algorithmPoolElementSize() {
  return std::max({sizeof(MeshMeshAlgorithm), sizeof(MeshConvexAlgorithm),
                   sizeof(MeshPlaneAlgorithm), sizeof(MeshConcaveAlgorithm)});
}

btDefaultCollisionConstructionInfo collisionConstructionInfo() {
  btDefaultCollisionConstructionInfo info;
  info.m_customCollisionAlgorithmMaxElementSize = static_cast<int>(algorithmPoolElementSize());
  return info;
}

void registerAlgorithms(btCollisionDispatcher& dispatcher,
                        btDefaultCollisionConfiguration& configuration) {
  // Bullet's pool allocator checks the requested size against its element size only with a
  // debug assert: in a release build an algorithm larger than an element overruns it.
  // Refuse at registration instead.
  const int element = configuration.getCollisionAlgorithmPool()->getElementSize();
  if (element < static_cast<int>(algorithmPoolElementSize())) {
    throw SettingsError(
        "adb::registerAlgorithms: the collision algorithm pool holds " +
        std::to_string(element) + " bytes per algorithm, MeshMeshAlgorithm needs " +
        std::to_string(algorithmPoolElementSize()) +
        ": set btDefaultCollisionConstructionInfo::m_customCollisionAlgorithmMaxElementSize "
        "to adb::algorithmPoolElementSize()");
  }
  // Function objects live as long as the program: dispatchers keep raw pointers to them.
  // The mesh-second order of each algorithm: Bullet's m_swapped flag of the factory.
  const auto swapped = [](auto f) {
    f.m_swapped = true;
    return f;
  };
  static CreateAlgorithm<MeshMeshAlgorithm> createMeshMesh;
  static CreateAlgorithm<MeshConvexAlgorithm> createMeshConvex;
  static CreateAlgorithm<MeshConvexAlgorithm> createConvexMesh =
      swapped(CreateAlgorithm<MeshConvexAlgorithm>{});
  const auto both = [&](int t0, int t1, btCollisionAlgorithmCreateFunc* f) {
    dispatcher.registerCollisionCreateFunc(t0, t1, f);
    dispatcher.registerClosestPointsCreateFunc(t0, t1, f);
  };
  both(CUSTOM_CONCAVE_SHAPE_TYPE, CUSTOM_CONCAVE_SHAPE_TYPE, &createMeshMesh);
  static CreateAlgorithm<MeshPlaneAlgorithm> createMeshPlane;
  static CreateAlgorithm<MeshPlaneAlgorithm> createPlaneMesh =
      swapped(CreateAlgorithm<MeshPlaneAlgorithm>{});
  both(CUSTOM_CONCAVE_SHAPE_TYPE, STATIC_PLANE_PROXYTYPE, &createMeshPlane);
  both(STATIC_PLANE_PROXYTYPE, CUSTOM_CONCAVE_SHAPE_TYPE, &createPlaneMesh);
  // Every other concave type (triangle meshes, heightfields, GImpact, ...), both orders.
  static CreateAlgorithm<MeshConcaveAlgorithm> createMeshConcave;
  static CreateAlgorithm<MeshConcaveAlgorithm> createConcaveMesh =
      swapped(CreateAlgorithm<MeshConcaveAlgorithm>{});
  for (int t = CONCAVE_SHAPES_START_HERE + 1; t < CUSTOM_CONCAVE_SHAPE_TYPE; ++t) {
    if (t == STATIC_PLANE_PROXYTYPE) continue;
    both(CUSTOM_CONCAVE_SHAPE_TYPE, t, &createMeshConcave);
    both(t, CUSTOM_CONCAVE_SHAPE_TYPE, &createConcaveMesh);
  }
  // Every convex type, both orders: Bullet's default would take MeshShape for an SDF shape.
  for (int t = 0; t < CONCAVE_SHAPES_START_HERE; ++t) {
    both(t, CUSTOM_CONCAVE_SHAPE_TYPE, &createConvexMesh);
    both(CUSTOM_CONCAVE_SHAPE_TYPE, t, &createMeshConvex);
  }
}

}  // namespace adb
