// MeshMeshAlgorithm: exact contacts between two MeshShapes.
#include "adb/bullet/mesh_mesh_algorithm.h"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <LinearMath/btPoolAllocator.h>

#include <algorithm>
#include <string>

#include "adb/bullet/mesh_concave_algorithm.h"
#include "adb/bullet/mesh_convex_algorithm.h"
#include "adb/bullet/mesh_plane_algorithm.h"
#include "adb/bullet/mesh_shape.h"
#include "adb/core/triangle_contact.h"
#include "conversions.h"

namespace adb {
namespace {

using detail::toBt;
using detail::toPose;
using detail::worldTriangle;

// Triangle pairs turned into contacts per pair and step at most: the manifold keeps 4 points
// (Bullet's reduction picks the widest), so more would cost without changing the result much.
constexpr std::uint32_t kMaxContactPairs = 64;

}  // namespace

void MeshMeshAlgorithm::processCollision(const btCollisionObjectWrapper* body0,
                                         const btCollisionObjectWrapper* body1,
                                         const btDispatcherInfo&, btManifoldResult* result) {
  manifoldFor(body0, body1, result);
  const auto* shape0 = static_cast<const MeshShape*>(body0->getCollisionShape());
  const auto* shape1 = static_cast<const MeshShape*>(body1->getCollisionShape());
  const Pose pose0 = toPose(body0->getWorldTransform());
  const Pose pose1 = toPose(body1->getWorldTransform());

  QuerySettings settings;
  settings.mode = QueryMode::Exact;
  settings.stopAtFirstHit = false;
  settings.maxWitnesses = kMaxContactPairs;
  collide(shape0->tree(), pose0, shape1->tree(), pose1, settings, m_scratch);

  // Normals are oriented from body 0 towards body 1 by the centres of their boxes: a stable
  // hint for the tie-breaks of triangleContact, frame after frame.
  btVector3 lo0, hi0, lo1, hi1;
  shape0->getAabb(body0->getWorldTransform(), lo0, hi0);
  shape1->getAabb(body1->getWorldTransform(), lo1, hi1);
  const btVector3 towards1 = 0.5 * ((lo1 + hi1) - (lo0 + hi0));
  const Vec3 hint(towards1.x(), towards1.y(), towards1.z());

  for (const Witness& w : m_scratch.witnesses()) {
    if (!w.isExact()) continue;
    Vec3 a[3], b[3];
    worldTriangle(shape0->tree(), pose0, w.triangleA, a);
    worldTriangle(shape1->tree(), pose1, w.triangleB, b);
    const TriangleContact c = triangleContact(a[0], a[1], a[2], b[0], b[1], b[2], hint);
    if (!c.valid) continue;
    // Bullet: the normal on B points from body 1 towards body 0, the point lies on body 1,
    // and a negative distance is a penetration.
    result->addContactPoint(toBt(-c.normal), toBt(c.pointOnB), static_cast<btScalar>(-c.depth));
  }
  result->refreshContactPoints();
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
  static CreateAlgorithm<MeshConvexAlgorithm> createConvexMesh;
  static CreateAlgorithm<MeshConvexAlgorithm> createMeshConvex =
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
