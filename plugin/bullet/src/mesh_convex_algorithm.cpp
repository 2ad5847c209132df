// MeshConvexAlgorithm: the triangles near a convex shape's oriented bounds, in closed form for
// spheres, capsules and boxes, by Bullet's GJK/EPA otherwise.
#include "mesh_convex_algorithm.h"

#include <BulletCollision/BroadphaseCollision/btDispatcher.h>
#include <BulletCollision/CollisionDispatch/btCollisionObjectWrapper.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/CollisionShapes/btTriangleShape.h>

#include <algorithm>
#include <limits>

#include "adb/bullet/mesh_shape.h"
#include "adb/core/box_query.h"
#include "adb/core/primitive_contact.h"
#include "contact_selection.h"
#include "conversions.h"
#include "near_face_corners.h"

namespace adb {
namespace {

// Mesh-box contacts are sampled per region (detail::kContactRegionLevel). A slack of a
// hundredth of the reach missed resting contacts by 17 % of their depth, a thousandth by 2 %
// once the trees were built by SAH (MeshConvexAgainstBullet asks for 0.1 %): none now.
constexpr double kDepthSlack = 0.0;

// The convex shape in the tree's local frame, as the closed-form tests need it.
struct LocalConvex {
  enum Kind { Sphere, Capsule, Box, General } kind = General;
  Pose pose;                // convex frame -> tree-local frame
  OrientedBox bounds;       // in mesh coordinates, grown by the reach: culls the tree
  OrientedBox box;          // Box: the box itself, tree-local
  Vec3 end0, end1;          // Capsule: its axis, tree-local (Sphere: end0 is the centre)
  double radius = 0.0;      // Sphere, Capsule
};

LocalConvex localConvex(const btConvexShape& shape, const Pose& convexInMesh,
                        const Vec3& treeOrigin, double reach) {
  LocalConvex c;
  c.pose = Pose{convexInMesh.rotation, convexInMesh.translation - treeOrigin};
  c.bounds.axes = convexInMesh.rotation;
  c.bounds.centre = convexInMesh.translation;
  switch (shape.getShapeType()) {
    case SPHERE_SHAPE_PROXYTYPE: {
      c.kind = LocalConvex::Sphere;
      c.radius = static_cast<const btSphereShape&>(shape).getRadius();
      c.end0 = c.pose.translation;
      c.bounds.half = Vec3::Constant(c.radius);
      break;
    }
    case CAPSULE_SHAPE_PROXYTYPE: {
      const auto& capsule = static_cast<const btCapsuleShape&>(shape);
      c.kind = LocalConvex::Capsule;
      c.radius = capsule.getRadius();
      const int up = capsule.getUpAxis();
      const Vec3 axis = c.pose.rotation.col(up) * capsule.getHalfHeight();
      c.end0 = c.pose.translation - axis;
      c.end1 = c.pose.translation + axis;
      c.bounds.half = Vec3::Constant(c.radius);
      c.bounds.half[up] += capsule.getHalfHeight();
      break;
    }
    case BOX_SHAPE_PROXYTYPE: {
      c.kind = LocalConvex::Box;
      c.box.centre = c.pose.translation;
      c.box.axes = c.pose.rotation;
      c.box.half = fromBt(static_cast<const btBoxShape&>(shape).getHalfExtentsWithMargin());
      c.bounds.half = c.box.half;
      break;
    }
    default: {
      // Any other convex shape: its own axis-aligned box in its own frame, oriented.
      btVector3 lo, hi;
      btTransform identity;
      identity.setIdentity();
      shape.getAabb(identity, lo, hi);
      const Vec3 centre = 0.5 * fromBt(lo + hi);
      c.bounds.centre += convexInMesh.rotation * centre;
      c.bounds.half = 0.5 * fromBt(hi - lo);
      c.box = OrientedBox{c.bounds.centre - treeOrigin, c.bounds.axes, c.bounds.half};
      break;
    }
  }
  c.bounds.half.array() += reach;
  return c;
}

// Turns closed-form contacts (tree-local, triangle side) into candidates in Bullet's terms.
void addCandidates(const PrimitiveContacts& found, const btTransform& meshPose,
                   const Vec3& treeOrigin, double meshMargin, double threshold, bool meshIsBody0,
                   int meshTriangle, detail::ContactSelection& selection) {
  for (int i = 0; i < found.count; ++i) {
    const PrimitiveContact& p = found.points[i];
    const double distance = p.separation - meshMargin;
    if (!(distance < threshold)) continue;
    const btVector3 onMesh = meshPose(toBt(p.onTriangle + treeOrigin));
    const btVector3 normal = meshPose.getBasis() * toBt(p.normal);  // mesh -> convex
    detail::CandidateContact c;
    c.distance = static_cast<btScalar>(distance);
    c.meshTriangle = meshTriangle;
    if (meshIsBody0) {
      // Body 1 is the convex shape: its point, and the normal pointing back at the mesh.
      c.normalOnB = -normal;
      c.pointOnB = onMesh + normal * c.distance;
    } else {
      c.normalOnB = normal;
      c.pointOnB = onMesh;
    }
    selection.add(c);
  }
}

// GJK/EPA per triangle near a general convex shape, as Bullet's convex-concave algorithm
// runs it, each triangle's points gathered in a scratch manifold and then offered to the
// selection: fed straight into the pair's manifold, a shallow point would replace a deeper
// one nearby and the deepest could be lost.
std::uint64_t generalConvexContacts(btDispatcher& dispatcher, const btCollisionObjectWrapper* meshWrap,
                           const btCollisionObjectWrapper* convexWrap, const LocalConvex& local,
                                    double reach, bool meshIsBody0,
                                    const btDispatcherInfo& info, btManifoldResult& result,
                                    detail::ContactSelection& selection) {
  std::uint64_t visited = 0;
  const auto* mesh = static_cast<const MeshShape*>(meshWrap->getCollisionShape());
  const AdbTree& tree = mesh->tree();
  const auto& vertices = tree.localVertices();
  const btTransform& meshPose = meshWrap->getWorldTransform();
  btPersistentManifold* pairManifold = result.getPersistentManifold();
  btPersistentManifold* scratch =
      dispatcher.getNewManifold(pairManifold->getBody0(), pairManifold->getBody1());
  result.setPersistentManifold(scratch);
  btTriangleShape triangle(btVector3(0, 0, 0), btVector3(0, 0, 0), btVector3(0, 0, 0));
  triangle.setMargin(mesh->getMargin());
  // The result's slot that holds the mesh: not always the algorithm's order (a compound
  // calls its child as (child, other) with a result made as (other, compound)).
  const bool meshInSlot0 = result.getBody0Internal() == meshWrap->getCollisionObject();
  const btCollisionObjectWrapper* saved = meshInSlot0 ? result.getBody0Wrap() : result.getBody1Wrap();
  visited += forEachTriangleNear(tree, local.bounds, [&](std::uint32_t t) {
    ++visited;
    const Triangle& tri = tree.triangles()[t];
    if (!triangleNearBox(vertices[tri[0]], vertices[tri[1]], vertices[tri[2]], local.box,
                         reach)) {
      return;
    }
    for (int k = 0; k < 3; ++k) triangle.m_vertices1[k] = toBt(vertices[tri[k]] + tree.origin());
    const int index = static_cast<int>(tree.meshTriangle(t));
    const btCollisionObjectWrapper triangleWrap(meshWrap, &triangle,
                                                meshWrap->getCollisionObject(), meshPose, 0,
                                                index);
    // The triangle takes the mesh's place: in the result's slot for it, and in the call in
    // this algorithm's order (the manifolds', which Bullet's points follow).
    const btCollisionObjectWrapper* first = meshIsBody0 ? &triangleWrap : convexWrap;
    const btCollisionObjectWrapper* second = meshIsBody0 ? convexWrap : &triangleWrap;
    if (meshInSlot0) {
      result.setBody0Wrap(&triangleWrap);
    } else {
      result.setBody1Wrap(&triangleWrap);
    }
    scratch->clearManifold();
    btCollisionAlgorithm* algorithm =
        dispatcher.findAlgorithm(first, second, scratch, BT_CONTACT_POINT_ALGORITHMS);
    algorithm->processCollision(first, second, info, &result);
    algorithm->~btCollisionAlgorithm();
    dispatcher.freeCollisionAlgorithm(algorithm);
    for (int i = 0; i < scratch->getNumContacts(); ++i) {
      const btManifoldPoint& p = scratch->getContactPoint(i);
      selection.add({p.m_normalWorldOnB, p.m_positionWorldOnB, p.getDistance(), index});
    }
  });
  if (meshInSlot0) {
    result.setBody0Wrap(saved);
  } else {
    result.setBody1Wrap(saved);
  }
  result.setPersistentManifold(pairManifold);
  dispatcher.releaseManifold(scratch);
  return visited;
}

// A mesh-convex pair as its contacts are computed: which body is which, how far contacts
// reach, and the convex shape in the tree's frame.
struct PairFrame {
  const btCollisionObjectWrapper* meshWrap;
  const btCollisionObjectWrapper* convexWrap;
  const MeshShape* mesh;
  bool meshIsBody0;
  double threshold;   // candidates up to this distance
  double meshMargin;
  double reach;       // triangles within this of the convex shape
  bool finite;        // the convex shape's pose in the mesh's frame is finite
  LocalConvex local;
  // Box: the way last step's contacts pushed the mesh out of the box, in the mesh's frame
  // (zero without contacts): boxTriangleContacts keeps to it.
  Vec3 pushHint = Vec3::Zero();
  // Box: the tree's regions that each give their deepest contacts are 2^regionLevel.
  int regionLevel = detail::kContactRegionLevel;
};

// PairFrame's pushHint: the last contacts' normals (ManifoldAlgorithm::lastNormalsOnB) as the
// direction they pushed the mesh, in the mesh's frame. Bullet's normal on body 1 points
// towards body 0.
PairFrame pairFrame(const btCollisionObjectWrapper* body0, const btCollisionObjectWrapper* body1,
                    bool meshIsBody0, double threshold, const btVector3& lastNormalsOnB) {
  PairFrame f;
  f.meshIsBody0 = meshIsBody0;
  f.meshWrap = meshIsBody0 ? body0 : body1;
  f.convexWrap = meshIsBody0 ? body1 : body0;
  f.mesh = static_cast<const MeshShape*>(f.meshWrap->getCollisionShape());
  const auto* convex = static_cast<const btConvexShape*>(f.convexWrap->getCollisionShape());
  // Candidates up to the threshold (and this step's speculative reach), from triangles
  // within that plus the mesh's margin.
  f.threshold = threshold;
  f.meshMargin = f.mesh->getMargin();
  f.reach = f.threshold + f.meshMargin;
  const Pose convexInMesh =
      toPose(f.meshWrap->getWorldTransform().inverseTimes(f.convexWrap->getWorldTransform()));
  f.finite = convexInMesh.rotation.allFinite() && convexInMesh.translation.allFinite();
  if (f.finite) f.local = localConvex(*convex, convexInMesh, f.mesh->tree().origin(), f.reach);
  const btVector3 push = meshIsBody0 ? lastNormalsOnB : -lastNormalsOnB;
  f.pushHint = fromBt(f.meshWrap->getWorldTransform().getBasis().transpose() * push);
  return f;
}

// Whether the closed-form tests cover the shape (localConvex's kinds other than General).
bool isClosedForm(const btCollisionShape& shape) {
  const int type = shape.getShapeType();
  return type == SPHERE_SHAPE_PROXYTYPE || type == CAPSULE_SHAPE_PROXYTYPE ||
         type == BOX_SHAPE_PROXYTYPE;
}

// Which way to push the mesh out of the box `box` (tree-local) when no contacts of last step
// say it: towards the side of the box the mesh's part inside it lies on. A body spawned, or
// first found, more than halfway into a thin box (a ledge, a floor) is mostly on the side it
// came from, where the box's nearest face is the far one. The corners and centroids of the
// triangles near the box that lie inside it, each in box axes scaled by the box's half
// extent (a thin box's thin axis speaks loudest), summed and turned back into the tree's
// frame; zero when none lies inside. Adds the nodes visited to `visited`.
Vec3 overlapSide(const AdbTree& tree, const OrientedBox& box, std::uint64_t& visited) {
  const auto& vertices = tree.localVertices();
  const Mat3 toBox = box.axes.transpose();
  const Vec3 inverseHalf = box.half.cwiseMax(1e-12).cwiseInverse();
  Vec3 side = Vec3::Zero();
  const auto addIfInside = [&](const Vec3& p) {
    const Vec3 q = toBox * (p - box.centre);
    if ((q.cwiseAbs().array() <= box.half.array()).all()) side += q.cwiseProduct(inverseHalf);
  };
  OrientedBox meshBox = box;
  meshBox.centre += tree.origin();
  visited += forEachTriangleNear(tree, meshBox, [&](std::uint32_t t) {
    const Triangle& tri = tree.triangles()[t];
    const Vec3& a = vertices[tri[0]];
    const Vec3& b = vertices[tri[1]];
    const Vec3& c = vertices[tri[2]];
    addIfInside(a);
    addIfInside(b);
    addIfInside(c);
    addIfInside((a + b + c) / 3.0);
  });
  const Vec3 hint = box.axes * side;
  return hint.allFinite() ? hint : Vec3::Zero();
}

// The closed-form contacts of a sphere, capsule or box against the triangles within reach,
// offered to `selection`; returns the work (triangles and nodes visited).
std::uint64_t closedFormContacts(const PairFrame& f, detail::ContactSelection& selection) {
  const AdbTree& tree = f.mesh->tree();
  const btTransform& meshPose = f.meshWrap->getWorldTransform();
  const auto& vertices = tree.localVertices();
  const LocalConvex& local = f.local;
  std::uint64_t visited = 0;
  Vec3 pushHint = f.pushHint;
  if (local.kind == LocalConvex::Box && pushHint.isZero(0.0)) {
    pushHint = overlapSide(tree, local.box, visited);
  }
  // Closed-form contacts of one triangle, offered to the selection; returns the deepest.
  const auto contactsOf = [&](std::uint32_t t) {
    ++visited;
    const Triangle& tri = tree.triangles()[t];
    const Vec3& a = vertices[tri[0]];
    const Vec3& b = vertices[tri[1]];
    const Vec3& c = vertices[tri[2]];
    PrimitiveContacts found;
    switch (local.kind) {
      case LocalConvex::Sphere:
        sphereTriangleContacts(local.end0, local.radius, a, b, c, f.reach, found);
        break;
      case LocalConvex::Capsule:
        capsuleTriangleContacts(local.end0, local.end1, local.radius, a, b, c, f.reach, found);
        break;
      default:
        boxTriangleContacts(local.box, a, b, c, f.reach, found, pushHint);
        break;
    }
    addCandidates(found, meshPose, tree.origin(), f.meshMargin, f.threshold, f.meshIsBody0,
                  static_cast<int>(tree.meshTriangle(t)), selection);
    double deepest = -std::numeric_limits<double>::infinity();
    for (int i = 0; i < found.count; ++i) deepest = std::max(deepest, -found.points[i].separation);
    return deepest;
  };
  if (local.kind == LocalConvex::Box) {
    // A box (a floor, a wall) has hundreds of triangles within reach of a resting body:
    // each region of the tree gives its deepest contacts (forEachDeepestTriangleNear).
    visited += forEachDeepestTriangleNear(tree, local.box, f.reach, f.regionLevel,
                                         kDepthSlack * f.reach, contactsOf);
  } else {
    visited += forEachTriangleNear(tree, local.bounds, [&](std::uint32_t t) { contactsOf(t); });
  }
  return visited;
}

// A fast body still apart from the convex shape: its speculative candidates are the closest
// triangles of each region of the tree, which may all lie on one side of its face (a gear at
// 30 m/s turned about them 1.9 cm into a box wall once the tree was built by SAH). As for a
// plane (mesh_plane_algorithm.cpp) and another mesh, the four corners of its root box's face
// towards the shape get the closest candidate's distance and normal (a hair closer: kept
// first), and hold the whole face.
void addSpeculativeCorners(const PairFrame& f, detail::ContactSelection& selection) {
  const detail::CandidateContact* closest = selection.closest();
  if (!closest || !(closest->distance > 0)) return;
  const btScalar distance =
      std::nextafter(closest->distance, -std::numeric_limits<btScalar>::infinity());
  const btVector3 normalOnB = closest->normalOnB;  // from body 1 towards body 0
  // Towards the shape from the mesh: against the normal when the mesh is body 0.
  const btVector3 towardsShape = f.meshIsBody0 ? -normalOnB : normalOnB;
  for (const btVector3& onMesh :
       detail::nearFaceCorners(*f.mesh, f.meshWrap->getWorldTransform(), towardsShape)) {
    // Bullet's point on A is the point on B plus normalOnB times the distance.
    const btVector3 pointOnB = f.meshIsBody0 ? onMesh - normalOnB * distance : onMesh;
    selection.add({normalOnB, pointOnB, distance, -1});
  }
}

}  // namespace

std::uint64_t MeshConvexAlgorithm::collideNow(const btCollisionObjectWrapper* body0,
                                             const btCollisionObjectWrapper* body1,
                                             const btDispatcherInfo& info,
                                             btManifoldResult* result) {
  btPersistentManifold* manifold = manifoldFor(body0, body1, result);
  detail::ContactSelection selection;
  if (gathersOffThread(body0, body1)) {  // the route the scheduler's pool takes, here at once
    const std::uint64_t work =
        gather(body0, body1, result->m_closestPointDistanceThreshold, selection);
    writeSelection(selection, *result);
    return work;
  }
  const PairFrame f = pairFrame(body0, body1, !m_swapped,
                                candidateThreshold(result->m_closestPointDistanceThreshold),
                                lastNormalsOnB());
  if (!f.finite) return 0;
  const std::uint64_t work = generalConvexContacts(*m_dispatcher, f.meshWrap, f.convexWrap,
                                                   f.local, f.reach, f.meshIsBody0, info,
                                                   *result, selection);
  selection.write(*result, f.meshIsBody0, *manifold);
  result->refreshContactPoints();
  return work;
}

// By the convex shape's type alone: deciding it must cost the stepping thread nothing.
bool MeshConvexAlgorithm::gathersOffThread(const btCollisionObjectWrapper* body0,
                                           const btCollisionObjectWrapper* body1) const {
  return isClosedForm(*(m_swapped ? body0 : body1)->getCollisionShape());
}

std::uint64_t MeshConvexAlgorithm::gather(const btCollisionObjectWrapper* body0,
                                          const btCollisionObjectWrapper* body1,
                                          btScalar closestPoints,
                                          detail::ContactSelection& selection) const {
  selection.clear();
  PairFrame f = pairFrame(body0, body1, !m_swapped, candidateThreshold(closestPoints),
                          lastNormalsOnB());
  f.regionLevel = contactRegionLevel();
  // A pose too far out for its relative pose to be finite offers nothing (acceptPoses has
  // refused non-finite poses already).
  if (!f.finite) return 0;
  const std::uint64_t work = closedFormContacts(f, selection);
  if (speculativeReach() > 0) addSpeculativeCorners(f, selection);
  return work;
}

double MeshConvexAlgorithm::candidateThreshold(btScalar closestPoints) const {
  return btMax(breakingThreshold(), closestPoints) + speculativeReach();
}

}  // namespace adb
