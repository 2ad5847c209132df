// MeshShape's ray and convex casts: Bullet's rayTest and convexSweepTest (and so the discrete
// world's CCD, which sweeps a sphere with convexSweepTest) walked through the ADB-tree along
// the segment, nearest leaf first, instead of every triangle in the box around the cast.
//
// Bullet reaches a custom concave shape only through processAllTriangles (btCollisionWorld's
// generic concave path), with a btTriangleRaycastCallback or a btTriangleConvexcastCallback
// whose members say what the cast is: MeshShape::processAllTriangles recognises them and
// comes here. The per-triangle tests are Bullet's own, on the mesh's own vertices, so the hits
// are the ones btBvhTriangleMeshShape gives for the same mesh.
#include <BulletCollision/CollisionShapes/btConvexShape.h>
#include <BulletCollision/CollisionShapes/btTriangleShape.h>
#include <BulletCollision/NarrowPhaseCollision/btContinuousConvexCollision.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btRaycastCallback.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "adb/bullet/mesh_shape.h"
#include "adb/core/ray_query.h"
#include "conversions.h"

namespace adb {
namespace {


// btTriangleRaycastCallback accepts a hit up to 1e-4 of the triangle's height beyond each
// edge (its edge_tolerance); the height is at most the longest edge, at most sqrt(3) times
// the largest extent of any box holding the triangle: 2e-4 of a node's extent covers it.
constexpr double kRayEdgePad = 2e-4;
// btContinuousConvexCollision reports an impact once the distance falls to 0.001 (its
// `radius`); twice that leaves room for GJK's own error on the distance.
constexpr double kCastDistancePad = 0.002;

// Bullet computes in btScalar: a point it finds can lie a few rounding errors of the
// coordinates' magnitude outside a box the core computed in double.
double roundingPad(const AdbTree& tree, const Vec3& from, const Vec3& to) {
  const Node& root = tree.root();
  const double mesh = (tree.origin().cwiseAbs() +
                       0.5 * (root.boxHi() - root.boxLo()).cwiseAbs())
                          .maxCoeff();
  const double query = std::max(from.cwiseAbs().maxCoeff(), to.cwiseAbs().maxCoeff());
  return 16.0 * static_cast<double>(std::numeric_limits<btScalar>::epsilon()) *
         std::max(mesh, query);
}

void meshCorners(const TriangleMesh& mesh, std::uint32_t triangle, btVector3 corners[3]) {
  const Triangle& t = mesh.triangles()[triangle];
  for (int k = 0; k < 3; ++k) corners[k] = toBt(mesh.vertices()[t[k]]);
}

}  // namespace

void MeshShape::performRaycast(btTriangleRaycastCallback* callback) const {
  const MeshData& d = data();
  SegmentQuery q;
  q.from = fromBt(callback->m_from);
  q.to = fromBt(callback->m_to);
  q.relativePad = kRayEdgePad;
  if (!q.from.allFinite() || !q.to.allFinite()) return;  // Bullet's test finds nothing either
  q.pad = roundingPad(d.tree, q.from, q.to);
  // The callback lowers m_hitFraction with each hit it keeps (the closest-hit callbacks) or
  // leaves it (all-hits ones): either way it is the bound the traversal prunes with.
  forEachTriangleAlongSegment(d.tree, q, static_cast<double>(callback->m_hitFraction),
                              [&](std::uint32_t t) {
                                const std::uint32_t m = d.tree.meshTriangle(t);
                                btVector3 corners[3];
                                meshCorners(d.mesh, m, corners);
                                callback->processTriangle(corners, 0, static_cast<int>(m));
                                return static_cast<double>(callback->m_hitFraction);
                              });
}

void MeshShape::performConvexcast(btTriangleConvexcastCallback* callback) const {
  const MeshData& d = data();
  const btConvexShape* convex = callback->m_convexShape;
  const btTransform worldToMesh = callback->m_triangleToWorld.inverse();
  const btTransform from = worldToMesh * callback->m_convexShapeFrom;
  const btTransform to = worldToMesh * callback->m_convexShapeTo;

  SegmentQuery q;
  q.from = fromBt(from.getOrigin());
  q.to = fromBt(to.getOrigin());
  if (!q.from.allFinite() || !q.to.allFinite()) return;
  // The convex's box about its origin, in the mesh's axes (margin included). A rotating
  // sweep passes through orientations between the two: the ball of the angular-motion disc
  // holds the shape in all of them.
  if (callback->m_convexShapeFrom.getBasis() == callback->m_convexShapeTo.getBasis()) {
    btVector3 lo, hi;
    convex->getAabb(btTransform(to.getBasis()), lo, hi);
    q.sweptLo = fromBt(lo);
    q.sweptHi = fromBt(hi);
  } else {
    const double r = static_cast<double>(convex->getAngularMotionDisc());
    q.sweptLo = Vec3::Constant(-r);
    q.sweptHi = Vec3::Constant(r);
  }
  q.pad = static_cast<double>(callback->m_triangleCollisionMargin) + kCastDistancePad +
          std::max(0.0, -static_cast<double>(callback->m_allowedPenetration)) +
          roundingPad(d.tree, q.from, q.to);

  // btTriangleConvexcastCallback::processTriangle never lowers m_hitFraction (it ignores
  // reportHit's answer), so the cast is made here, as it makes it, to know each fraction.
  btScalar bound = callback->m_hitFraction;
  forEachTriangleAlongSegment(
      d.tree, q, static_cast<double>(bound), [&](std::uint32_t t) {
        const std::uint32_t m = d.tree.meshTriangle(t);
        btVector3 corners[3];
        meshCorners(d.mesh, m, corners);
        btTriangleShape triangle(corners[0], corners[1], corners[2]);
        triangle.setMargin(callback->m_triangleCollisionMargin);
        btVoronoiSimplexSolver simplex;
        btGjkEpaPenetrationDepthSolver penetration;
        btContinuousConvexCollision caster(convex, &triangle, &simplex, &penetration);
        btConvexCast::CastResult result;
        result.m_fraction = btScalar(1.);
        result.m_allowedPenetration = callback->m_allowedPenetration;
        if (caster.calcTimeOfImpact(callback->m_convexShapeFrom, callback->m_convexShapeTo,
                                    callback->m_triangleToWorld, callback->m_triangleToWorld,
                                    result) &&
            result.m_normal.length2() > btScalar(0.0001) && result.m_fraction < bound) {
          result.m_normal.normalize();
          const btScalar limit = callback->reportHit(result.m_normal, result.m_hitPoint,
                                                     result.m_fraction, 0, static_cast<int>(m));
          if (limit < bound) bound = limit;
        }
        return static_cast<double>(bound);
      });
}

}  // namespace adb
