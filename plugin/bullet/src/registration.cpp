// The one registration point: every create function of adb's algorithms, and the pool size
// computed from the algorithms' own sizes.
#include "adb/bullet/registration.h"

#include <LinearMath/btPoolAllocator.h>

#include <algorithm>
#include <string>

#include "adb/core/tree.h"  // SettingsError
#include "mesh_concave_algorithm.h"
#include "mesh_convex_algorithm.h"
#include "mesh_mesh_algorithm.h"
#include "mesh_plane_algorithm.h"

namespace adb {

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
