// GImpact peer. Choices:
//  - The collision algorithm is created once per case (untimed) and reused for every query,
//    as a Bullet world keeps one per overlapping pair from frame to frame; each query times
//    processCollision alone (GImpact clears and refills its manifold inside it).
//  - The shape's collision margin is 0: the default margin (0.04 model units) would report
//    contacts between triangles that do not touch, and the question here is intersection.
//  - Bullet's precision is that of adb::bullet (float by default): vertices and poses are
//    rounded to btScalar, so answers may differ from the double-precision methods on grazing
//    contacts. Such differences show up in summary.csv's error_pct for gimpact.
#include "gimpact_peer.h"

#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObject.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h>
#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>

#include <stdexcept>
#include <vector>

#include "adb/bullet/precision.h"  // fails to compile at a Bullet precision other than adb's
#include "adb/bullet/triangle_arrays.h"

namespace adb::tradeoff {
namespace {

btTransform toBt(const Pose& p) {
  const Mat3& r = p.rotation;
  const btMatrix3x3 basis(
      static_cast<btScalar>(r(0, 0)), static_cast<btScalar>(r(0, 1)), static_cast<btScalar>(r(0, 2)),
      static_cast<btScalar>(r(1, 0)), static_cast<btScalar>(r(1, 1)), static_cast<btScalar>(r(1, 2)),
      static_cast<btScalar>(r(2, 0)), static_cast<btScalar>(r(2, 1)), static_cast<btScalar>(r(2, 2)));
  const Vec3& t = p.translation;
  return btTransform(basis, btVector3(static_cast<btScalar>(t.x()), static_cast<btScalar>(t.y()),
                                      static_cast<btScalar>(t.z())));
}

// One model's GImpact shape. GImpact reads the mesh through the arrays: they must outlive the
// shape (members are destroyed in reverse order).
struct GimpactShape {
  std::unique_ptr<TriangleArrays> arrays;
  std::unique_ptr<btGImpactMeshShape> shape;

  explicit GimpactShape(const TriangleMesh& mesh)
      : arrays(std::make_unique<TriangleArrays>(mesh)),
        shape(std::make_unique<btGImpactMeshShape>(arrays->array.get())) {
    shape->setMargin(0);
    shape->updateBound();  // builds the box tree once
  }
};

}  // namespace

struct GimpactPeer::Impl {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDispatcherInfo dispatchInfo;
  std::unique_ptr<GimpactShape> shapeA, shapeB;  // shapeB empty: two copies of shapeA
  btCollisionObject objectA, objectB;
  btCollisionAlgorithm* algorithm = nullptr;
  btManifoldArray manifolds;

  Impl() { btGImpactCollisionAlgorithm::registerAlgorithm(&dispatcher); }
  ~Impl() { releaseAlgorithm(); }

  void releaseAlgorithm() {
    if (!algorithm) return;
    algorithm->~btCollisionAlgorithm();  // allocated in the dispatcher's pool
    dispatcher.freeCollisionAlgorithm(algorithm);
    algorithm = nullptr;
  }

  btGImpactMeshShape* shapeOfA() const { return shapeA->shape.get(); }
  btGImpactMeshShape* shapeOfB() const { return (shapeB ? shapeB : shapeA)->shape.get(); }

  void buildShapes(const Model& a, const Model& b) {
    releaseAlgorithm();
    shapeA.reset();  // free the last case's shapes first
    shapeB.reset();
    shapeA = std::make_unique<GimpactShape>(a.mesh);
    if (&a != &b) shapeB = std::make_unique<GimpactShape>(b.mesh);
    objectA.setCollisionShape(shapeOfA());
    objectB.setCollisionShape(shapeOfB());
  }

  void createAlgorithm() {
    const btCollisionObjectWrapper a(nullptr, shapeOfA(), &objectA, objectA.getWorldTransform(), -1, -1);
    const btCollisionObjectWrapper b(nullptr, shapeOfB(), &objectB, objectB.getWorldTransform(), -1, -1);
    algorithm = dispatcher.findAlgorithm(&a, &b, nullptr, BT_CONTACT_POINT_ALGORITHMS);
    if (!algorithm) throw std::runtime_error("Bullet found no GImpact algorithm");
  }

  bool collide(const Pose& poseA, const Pose& poseB) {
    objectA.setWorldTransform(toBt(poseA));
    objectB.setWorldTransform(toBt(poseB));
    const btCollisionObjectWrapper a(nullptr, shapeOfA(), &objectA, objectA.getWorldTransform(), -1, -1);
    const btCollisionObjectWrapper b(nullptr, shapeOfB(), &objectB, objectB.getWorldTransform(), -1, -1);
    btManifoldResult result(&a, &b);
    algorithm->processCollision(&a, &b, dispatchInfo, &result);
    manifolds.resize(0);
    algorithm->getAllContactManifolds(manifolds);
    for (int i = 0; i < manifolds.size(); ++i) {
      if (manifolds[i]->getNumContacts() > 0) return true;
    }
    return false;
  }
};

GimpactPeer::GimpactPeer() : m_impl(std::make_unique<Impl>()) {}
GimpactPeer::~GimpactPeer() = default;

void GimpactPeer::prepare(const Model& a, const Model& b) {
  m_impl->buildShapes(a, b);
  m_impl->createAlgorithm();
}

Answer GimpactPeer::query(const Pose& a, const Pose& b) {
  Answer answer;
  answer.collides = m_impl->collide(a, b);
  answer.confidence = 1.0;
  return answer;  // nodePairs stays -1: GImpact does not report its box tests
}

}  // namespace adb::tradeoff
