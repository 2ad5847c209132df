// MeshConvexAlgorithm: convex shapes against the triangles of a MeshShape.
#include "adb/bullet/mesh_convex_algorithm.h"

#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>

#include "adb/bullet/mesh_shape.h"

namespace adb {

MeshConvexAlgorithm::MeshConvexAlgorithm(const btCollisionAlgorithmConstructionInfo& ci,
                                         const btCollisionObjectWrapper* body0,
                                         const btCollisionObjectWrapper* body1, bool swapped)
    : btActivatingCollisionAlgorithm(ci, body0, body1),
      m_swapped(swapped),
      m_triangles(ci.m_dispatcher1, body0, body1, swapped) {}

void MeshConvexAlgorithm::processCollision(const btCollisionObjectWrapper* body0,
                                           const btCollisionObjectWrapper* body1,
                                           const btDispatcherInfo& info,
                                           btManifoldResult* result) {
  const btCollisionObjectWrapper* convex = m_swapped ? body1 : body0;
  const btCollisionObjectWrapper* mesh = m_swapped ? body0 : body1;
  const auto* shape = static_cast<const MeshShape*>(mesh->getCollisionShape());
  result->setPersistentManifold(m_triangles.m_manifoldPtr);
  // The callback computes the convex shape's box in the mesh's frame, then tests each
  // triangle the tree reports near it (MeshShape::processAllTriangles).
  m_triangles.setTimeStepAndCounters(shape->getMargin(), info, convex, mesh, result);
  m_triangles.m_manifoldPtr->setBodies(convex->getCollisionObject(), mesh->getCollisionObject());
  shape->processAllTriangles(&m_triangles, m_triangles.getAabbMin(), m_triangles.getAabbMax());
  result->refreshContactPoints();
  m_triangles.clearWrapperData();
}

void MeshConvexAlgorithm::getAllContactManifolds(btManifoldArray& manifolds) {
  if (m_triangles.m_manifoldPtr) manifolds.push_back(m_triangles.m_manifoldPtr);
}

}  // namespace adb
