// Pair-kind scenes: one mesh and one convex shape, over adb's shape or Bullet's.
#include "pair_kind_scene.h"

#include <algorithm>
#include <cmath>

namespace adb::tools {
namespace {

// Sizes relative to the mesh's bounding-box diagonal: small bodies against a large mesh,
// as parts in a bin, and a wall far larger than the mesh.
constexpr double kSmall = 0.05;
constexpr double kWallHalfWidth = 2.0;
constexpr double kWallHalfThickness = 0.1;
// How far a body's deepest point is inside the mesh, as a fraction of a small body's size:
// the depth at which a pile's bodies rest on each other.
constexpr double kPenetration = 0.01;

btVector3 bt(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
                   static_cast<btScalar>(v.z()));
}

double sizeOf(const TriangleMesh& mesh) { return mesh.bounds().extent().norm(); }

std::unique_ptr<btCollisionShape> makeConvex(ConvexKind kind, double size) {
  const auto s = static_cast<btScalar>(size * kSmall);
  switch (kind) {
    case ConvexKind::Box:
      return std::make_unique<btBoxShape>(btVector3(s, 0.7f * s, 0.5f * s));
    case ConvexKind::Wall: {
      const auto w = static_cast<btScalar>(size * kWallHalfWidth);
      return std::make_unique<btBoxShape>(
          btVector3(w, static_cast<btScalar>(size * kWallHalfThickness), w));
    }
    case ConvexKind::Sphere:
      return std::make_unique<btSphereShape>(s);
    case ConvexKind::Capsule:
      return std::make_unique<btCapsuleShape>(0.6f * s, 1.5f * s);
    case ConvexKind::Cylinder:
      return std::make_unique<btCylinderShape>(btVector3(s, 0.8f * s, s));
    case ConvexKind::Hull: {
      auto hull = std::make_unique<btConvexHullShape>();
      // An irregular octahedron.
      const btScalar points[6][3] = {{s, 0, 0},  {-0.8f * s, 0, 0}, {0, 1.2f * s, 0},
                                     {0, -s, 0}, {0, 0, 0.7f * s},  {0, 0, -s}};
      for (const auto& p : points) hull->addPoint(btVector3(p[0], p[1], p[2]), false);
      hull->recalcLocalAabb();
      return hull;
    }
  }
  return nullptr;
}

btMatrix3x3 randomBasis(std::mt19937& rng) {
  std::normal_distribution<double> g;
  btQuaternion q(static_cast<btScalar>(g(rng)), static_cast<btScalar>(g(rng)),
                 static_cast<btScalar>(g(rng)), static_cast<btScalar>(g(rng)));
  q.normalize();
  return btMatrix3x3(q);
}

}  // namespace

const char* kindName(ConvexKind kind) {
  switch (kind) {
    case ConvexKind::Box: return "box";
    case ConvexKind::Wall: return "wall";
    case ConvexKind::Sphere: return "sphere";
    case ConvexKind::Capsule: return "capsule";
    case ConvexKind::Cylinder: return "cylinder";
    case ConvexKind::Hull: return "hull";
  }
  return "?";
}

void PairWorld::collide(const btTransform& meshPose, const btTransform& convexPose) {
  mesh.setWorldTransform(meshPose);
  convex.setWorldTransform(convexPose);
  // The poses are unrelated to each other: last pose's points must not persist into this.
  for (int i = 0; i < dispatcher->getNumManifolds(); ++i) {
    dispatcher->getManifoldByIndexInternal(i)->clearManifold();
  }
  world->performDiscreteCollisionDetection();
}

int PairWorld::contactPoints() const {
  int points = 0;
  for (int i = 0; i < dispatcher->getNumManifolds(); ++i) {
    points += dispatcher->getManifoldByIndexInternal(i)->getNumContacts();
  }
  return points;
}

double PairWorld::deepestPenetration() const {
  double deepest = 0.0;
  for (int i = 0; i < dispatcher->getNumManifolds(); ++i) {
    const btPersistentManifold* m = dispatcher->getManifoldByIndexInternal(i);
    for (int k = 0; k < m->getNumContacts(); ++k) {
      deepest = std::max(deepest, -static_cast<double>(m->getContactPoint(k).getDistance()));
    }
  }
  return deepest;
}

std::unique_ptr<PairWorld> makePairWorld(const TriangleMesh& mesh, ConvexKind kind, bool adb) {
  auto w = std::make_unique<PairWorld>();
  w->configuration =
      std::make_unique<btDefaultCollisionConfiguration>(collisionConstructionInfo());
  w->dispatcher = std::make_unique<btCollisionDispatcher>(w->configuration.get());
  if (adb) {
    registerAlgorithms(*w->dispatcher, *w->configuration);
    w->meshShape = std::make_unique<MeshShape>(MeshData::build(mesh));
  } else {
    w->triangles = std::make_unique<TriangleArrays>(mesh);
    w->meshShape = std::make_unique<btBvhTriangleMeshShape>(w->triangles->array.get(), true);
  }
  w->convexShape = makeConvex(kind, sizeOf(mesh));
  w->broadphase = std::make_unique<btDbvtBroadphase>();
  w->world = std::make_unique<btCollisionWorld>(w->dispatcher.get(), w->broadphase.get(),
                                                w->configuration.get());
  w->mesh.setCollisionShape(w->meshShape.get());
  w->convex.setCollisionShape(w->convexShape.get());
  w->world->addCollisionObject(&w->mesh);
  w->world->addCollisionObject(&w->convex);
  return w;
}

std::vector<std::pair<btTransform, btTransform>> surfacePoses(const TriangleMesh& mesh,
                                                             const btConvexShape& convex,
                                                             ConvexKind kind, int count,
                                                             unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, mesh.triangles().size() - 1);
  // Resting contact, as bodies in a pile meet: the convex shape's deepest point is
  // kPenetration of a small body's size inside the mesh.
  const auto depth = static_cast<btScalar>(kPenetration * kSmall * sizeOf(mesh));
  std::vector<std::pair<btTransform, btTransform>> poses;
  while (static_cast<int>(poses.size()) < count) {
    const btTransform meshPose(randomBasis(rng), btVector3(0, 0, 0));
    const btMatrix3x3 basis = randomBasis(rng);
    if (kind == ConvexKind::Wall) {
      // A floor under the mesh: the wall's +y face, along a random direction, meets the
      // mesh's lowest vertex along it.
      const btVector3 up = basis.getColumn(1);
      btVector3 lowest = meshPose(bt(mesh.vertices()[0]));
      for (const Vec3& v : mesh.vertices()) {
        const btVector3 x = meshPose(bt(v));
        if (x.dot(up) < lowest.dot(up)) lowest = x;
      }
      const btScalar half = static_cast<const btBoxShape&>(convex).getHalfExtentsWithMargin().y();
      poses.emplace_back(meshPose, btTransform(basis, lowest + up * (depth - half)));
      continue;
    }
    // A small body on a random triangle: its furthest point towards the triangle's back.
    const Triangle& t = mesh.triangles()[pick(rng)];
    const Vec3& a = mesh.vertices()[t[0]];
    const Vec3& b = mesh.vertices()[t[1]];
    const Vec3& c = mesh.vertices()[t[2]];
    const Vec3 n = (b - a).cross(c - a);
    if (!(n.norm() > 0.0)) continue;  // a degenerate triangle has no side
    const btVector3 onSurface = meshPose(bt((a + b + c) / 3.0));
    const btVector3 normal = meshPose.getBasis() * bt(n.normalized());
    const btVector3 deepest = convex.localGetSupportingVertex(basis.transpose() * -normal);
    poses.emplace_back(meshPose, btTransform(basis, onSurface - normal * depth - basis * deepest));
  }
  return poses;
}

}  // namespace adb::tools
