// MeshConcaveAlgorithm: the other shape's triangles near the mesh, each against the mesh
// triangles near it, decided by the exact triangle test.
#include "mesh_concave_algorithm.h"

#include <BulletCollision/BroadphaseCollision/btDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btConcaveShape.h>
#include <BulletCollision/CollisionShapes/btTriangleCallback.h>

#include "adb/bullet/mesh_shape.h"
#include "adb/core/box_query.h"
#include "adb/core/triangle_contact.h"
#include "adb/core/triangle_test.h"
#include "conversions.h"

namespace adb {
namespace {

using detail::worldTriangle;

// Intersecting triangle pairs turned into contacts per pair and step at most (the manifold
// keeps the widest 4).
constexpr int kMaxContactPairs = 64;

struct TriangleVsMesh : public btTriangleCallback {
  const AdbTree* tree;
  Pose meshPose, otherPose;
  Mat3 worldToMesh;  // inverse of the mesh rotation
  bool meshIsBody0;
  Vec3 hint;  // from body 0 towards body 1
  btManifoldResult* result;
  int contacts = 0;
  std::uint64_t visited = 0;  // their triangles and the mesh triangles near each

  void processTriangle(btVector3* corners, int, int) override {
    ++visited;
    if (contacts >= kMaxContactPairs) return;
    Vec3 other[3];
    Aabb box;  // the other triangle's box in the mesh's coordinates
    for (int k = 0; k < 3; ++k) {
      other[k] = otherPose.apply(fromBt(corners[k]));
      box.grow(worldToMesh * (other[k] - meshPose.translation));
    }
    forEachTriangleNear(*tree, box, [&](std::uint32_t t) {
      ++visited;
      if (contacts >= kMaxContactPairs) return;
      Vec3 mine[3];
      worldTriangle(*tree, meshPose, t, mine);
      const Vec3* a = meshIsBody0 ? mine : other;
      const Vec3* b = meshIsBody0 ? other : mine;
      if (!trianglesIntersect(a[0], a[1], a[2], b[0], b[1], b[2])) return;
      const TriangleContact c = triangleContact(a[0], a[1], a[2], b[0], b[1], b[2], hint);
      if (!c.valid) return;
      // Bullet: the normal on body 1 points towards body 0; a negative distance penetrates.
      result->addContactPoint(toBt(-c.normal), toBt(c.pointOnB), static_cast<btScalar>(-c.depth));
      ++contacts;
    });
  }
};

}  // namespace

std::uint64_t MeshConcaveAlgorithm::collideNow(const btCollisionObjectWrapper* body0,
                                              const btCollisionObjectWrapper* body1,
                                              const btDispatcherInfo&, btManifoldResult* result) {
  manifoldFor(body0, body1, result);
  const btCollisionObjectWrapper* meshWrap = m_swapped ? body1 : body0;
  const btCollisionObjectWrapper* otherWrap = m_swapped ? body0 : body1;
  const auto* mesh = static_cast<const MeshShape*>(meshWrap->getCollisionShape());
  const auto* other = static_cast<const btConcaveShape*>(otherWrap->getCollisionShape());

  TriangleVsMesh cb;
  cb.tree = &mesh->tree();
  cb.meshPose = toPose(meshWrap->getWorldTransform());
  cb.otherPose = toPose(otherWrap->getWorldTransform());
  cb.worldToMesh = cb.meshPose.rotation.inverse();
  cb.meshIsBody0 = !m_swapped;
  cb.result = result;
  btVector3 lo0, hi0, lo1, hi1;
  body0->getCollisionShape()->getAabb(body0->getWorldTransform(), lo0, hi0);
  body1->getCollisionShape()->getAabb(body1->getWorldTransform(), lo1, hi1);
  cb.hint = fromBt(0.5 * ((lo1 + hi1) - (lo0 + hi0)));

  // The mesh's box in the other shape's frame: only the other's triangles there are visited.
  btVector3 lo, hi;
  mesh->getAabb(otherWrap->getWorldTransform().inverse() * meshWrap->getWorldTransform(), lo, hi);
  other->processAllTriangles(&cb, lo, hi);
  result->refreshContactPoints();
  return cb.visited;
}

}  // namespace adb
