// Demo and benchmark support: one mesh and one convex shape in a btCollisionWorld, twice —
// the mesh as an adb::MeshShape (adb's algorithms registered) and as a
// btBvhTriangleMeshShape (Bullet's own btConvexConcaveCollisionAlgorithm) — with poses
// that put the convex shape across the mesh's surface. Shared by adb-bench-pairs and the
// Bullet tests that compare the two.
#pragma once

#include <btBulletCollisionCommon.h>

#include <memory>
#include <random>
#include <string>
#include <vector>

#include "adb/bullet/registration.h"
#include "adb/bullet/mesh_shape.h"
#include "adb/core/mesh.h"
#include "adb/bullet/triangle_arrays.h"

namespace adb::tools {

/// The convex shapes a pair-kind scene can hold. Wall: a box much larger than the mesh,
/// tilted, with a face through the mesh (a bin's wall or floor).
enum class ConvexKind { Box, Wall, Sphere, Capsule, Cylinder, Hull };

const char* kindName(ConvexKind kind);

/// A collision world holding one mesh and one convex shape.
struct PairWorld {
  std::unique_ptr<btDefaultCollisionConfiguration> configuration;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  std::unique_ptr<btDbvtBroadphase> broadphase;
  std::unique_ptr<btCollisionWorld> world;
  std::unique_ptr<TriangleArrays> triangles;  // the Bullet mesh's arrays
  std::unique_ptr<btCollisionShape> meshShape, convexShape;
  btCollisionObject mesh, convex;

  /// Places both bodies, forgets the last pose's contacts and runs the world's collision
  /// detection once.
  void collide(const btTransform& meshPose, const btTransform& convexPose);
  /// Contact points in the manifolds, and the deepest penetration (>= 0) among them.
  int contactPoints() const;
  double deepestPenetration() const;
};

/// The same scene over an adb MeshShape (`adb` true) or a btBvhTriangleMeshShape.
std::unique_ptr<PairWorld> makePairWorld(const TriangleMesh& mesh, ConvexKind kind, bool adb);

/// `count` seeded pose pairs (mesh, convex) of resting contact, both rotated at random: a
/// small convex shape's deepest point 1 % of its size inside the centre of a random
/// triangle; a wall under the mesh's lowest vertex along a random direction, as deep.
std::vector<std::pair<btTransform, btTransform>> surfacePoses(const TriangleMesh& mesh,
                                                             const btConvexShape& convex,
                                                             ConvexKind kind, int count,
                                                             unsigned seed);

}  // namespace adb::tools
