// SceneWorld: a scene built into a Bullet world with only what its effects ask for, stepped
// and measured.
//
// - overlap: a btCollisionWorld whose broadphase pairs get boolean queries (adb's traversal
//   for mesh-mesh pairs, within the step's budget; Bullet's pair test for the rest). No
//   contact generation, no solver, no rigid bodies. Begin and end events per pair.
// - contacts: a btCollisionWorld whose dispatcher writes contact manifolds. No solver.
// - dynamics: a btDiscreteDynamicsWorld with only the extras listed: without `friction`
//   every body has zero friction, without `restitution` zero restitution, without `sleeping`
//   no body sleeps, without `ccd` no swept tests, without `soft_contacts` plausible contacts
//   push as hard as exact ones.
//
// Outside dynamics nothing responds: static and dynamic bodies hold their poses unless they
// were given a velocity, which they keep (no gravity); kinematic bodies follow their motions
// in every kind of scene.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "adb/bullet/frame_budget.h"
#include "adb/core/mesh.h"
#include "adb/scene/penetration_probe.h"
#include "adb/scene/scene.h"

class btCollisionShape;
class btCollisionWorld;
namespace adb {
struct MeshData;
}
class btDiscreteDynamicsWorld;

namespace adb::scene {

/// Which collision code the scene's meshes get.
enum class Backend {
  Adb,      ///< adb's MeshShape under the scene's per-step budget
  Exact,    ///< adb's MeshShape with no budget: every pair exact
  GImpact,  ///< Bullet's btGImpactMeshShape (moving) and btBvhTriangleMeshShape (static)
  /// Moving meshes decomposed into convex shapes by a ConvexShapeMaker (adb-demo's: Bullet's
  /// HACD), static ones as btBvhTriangleMeshShape: the peer users prepare instead of adb.
  Convex,
};
const char* toString(Backend backend);
/// "adb", "exact", "gimpact" or "convex"; throws std::invalid_argument naming the value
/// otherwise.
Backend parseBackend(const std::string& name);
/// Whether the backend's meshes are adb's MeshShape (collided by adb's dispatcher).
inline bool usesAdbShapes(Backend backend) {
  return backend == Backend::Adb || backend == Backend::Exact;
}

/// Backend::Convex: a moving mesh's collision shape (in the mesh data's frame, its principal
/// frame), made once per mesh and shared by its bodies. The world keeps every shape returned
/// (a compound's children, say); the body's shape comes last.
using ConvexShapeMaker =
    std::function<std::vector<std::unique_ptr<btCollisionShape>>(const MeshData& mesh)>;

/// What the runner built for the scene's effects.
struct BuildReport {
  Effects::Kind effects = Effects::Kind::Dynamics;
  bool dynamicsWorld = false;      ///< a btDiscreteDynamicsWorld (else a btCollisionWorld)
  bool solver = false;             ///< a constraint solver
  bool rigidBodies = false;        ///< btRigidBody objects (else btCollisionObject)
  bool contactGeneration = false;  ///< the narrow phase writes contact manifolds
  bool booleanQueries = false;     ///< overlap: a yes/no query per broadphase pair
  bool budget = false;             ///< a per-step budget is in force
  bool ccd = false;                ///< swept tests for fast dynamic bodies
  bool sleeping = false;           ///< bodies may fall asleep
  int bodies = 0;
  int meshBodies = 0;              ///< bodies whose shape is a triangle mesh
  std::size_t triangles = 0;       ///< over the mesh bodies
  double buildSeconds = 0.0;       ///< reading and generating meshes, building trees and shapes
  /// One line: "btCollisionWorld, boolean queries, no contacts, no solver, no rigid bodies".
  std::string describe() const;
};

/// A contact point after a step (contacts and dynamics scenes).
struct ContactPoint {
  Vec3 position = Vec3::Zero();  ///< on the second body, world frame
  double depth = 0.0;            ///< penetration, >= 0 when touching
  double confidence = 1.0;       ///< of the pair that wrote it (1: exact)
  std::uint32_t body0 = 0, body1 = 0;  ///< indices into Scene::bodies
};

/// A pair of bodies that a budget cut (adb backend): its contacts are plausible, not exact.
struct CutPair {
  std::uint32_t body0 = 0, body1 = 0;
  double confidence = 1.0;
};

/// An overlap scene's event: a pair of bodies began or ended overlapping.
struct OverlapEvent {
  int step = 0;
  double time = 0.0;   ///< seconds, at the end of the step
  bool begin = true;   ///< false: the pair stopped overlapping
  std::uint32_t body0 = 0, body1 = 0;
  /// The probability that the pair's answer this step is right (1 when exact).
  double confidence = 1.0;
};

/// A pair of bodies overlapping after an overlap scene's step.
struct OverlapPair {
  std::uint32_t body0 = 0, body1 = 0;  ///< body0 < body1
  double confidence = 1.0;             ///< that they overlap (1 when exact)
};

/// One step's figures.
struct StepRecord {
  int step = 0;             ///< 1 for the first step
  double time = 0.0;        ///< simulated seconds at the end of the step
  double seconds = 0.0;     ///< wall clock of the step: collision and whatever effects
  /// Of the per-step budget, the share the adb pairs used (0 without a budget; may pass 1:
  /// a time budget is overshot by up to one pair's contact writing).
  double budgetUse = 0.0;
  std::uint32_t meshPairs = 0;  ///< mesh-mesh pairs whose boxes overlapped
  std::uint32_t cutPairs = 0;   ///< of those, cut by the budget
  double meanConfidence = 1.0;  ///< over the mesh-mesh pairs (1 when none)
  double worstConfidence = 1.0;
  std::uint32_t overlapping = 0;  ///< overlap: pairs overlapping after the step
  std::uint32_t events = 0;       ///< overlap: events this step
  std::uint32_t contacts = 0;     ///< contact points after the step
  double penetration = 0.0;       ///< deepest contact point, >= 0
  double kinetic = 0.0;           ///< dynamics: kinetic energy of the dynamic bodies, J
  double energy = 0.0;            ///< dynamics: kinetic plus potential (gravity), J
  int atRest = 0;                 ///< dynamics: bodies slower than 0.05 m/s and 0.05 rad/s
  int asleep = 0;                 ///< dynamics: bodies Bullet has deactivated (sleeping)
  /// Dynamic bodies lost: out of world.bounds (WorldSpec::bounds), or, in a scene without
  /// bounds, with their centre below the lowest static body by more than their size.
  int lost = 0;
  /// How far the deepest vertex of a dynamic mesh body reaches out of world.bounds (into a
  /// bin's floor or a wall), from the geometry whatever the contacts say; >= 0. And the same
  /// over that body's size (its box's diagonal), the worst body.
  double outOfBounds = 0.0;
  double outOfBoundsRelative = 0.0;
  FrameStats frame;               ///< adb backends, contacts and dynamics: the dispatcher's
};

class SceneWorld {
 public:
  /// Builds the world: reads mesh files (adb::io), generates models, builds trees and shapes.
  /// Throws SceneError naming the shape of a mesh file that cannot be read.
  /// Backend::Convex needs `convex` (std::invalid_argument otherwise); the others ignore it.
  SceneWorld(Scene scene, Backend backend, ConvexShapeMaker convex = {});
  ~SceneWorld();
  SceneWorld(const SceneWorld&) = delete;
  SceneWorld& operator=(const SceneWorld&) = delete;

  /// Advances one step (world.time_step, in world.substeps fixed substeps) and measures it.
  const StepRecord& step();
  const StepRecord& last() const;

  const Scene& scene() const;
  Backend backend() const;
  const BuildReport& built() const;

  std::size_t bodyCount() const;
  /// The body's shape as triangles in the body's frame (primitives tessellated; a plane as a
  /// large square): what a picture draws at bodyPose().
  const TriangleMesh& displayMesh(std::size_t body) const;
  Pose bodyPose(std::size_t body) const;
  /// The body's pose in the scene file's terms (that of its mesh's own frame, not of the
  /// principal frame Bullet's body uses): a scene written with these poses starts here.
  Pose scenePose(std::size_t body) const;
  bool isDynamic(std::size_t body) const;

  /// After the last step: contact points (contacts and dynamics), the pairs a budget cut, and
  /// the overlap events (overlap).
  const std::vector<ContactPoint>& contacts() const;
  const std::vector<CutPair>& cutPairs() const;
  const std::vector<OverlapEvent>& events() const;
  /// Overlap scenes: the pairs overlapping after the last step, sorted by body indices.
  const std::vector<OverlapPair>& overlapping() const;

  /// Body-body penetration measured from the geometry (adb/scene/penetration_probe.h),
  /// between dynamic mesh bodies, whatever the contacts say: the same measure for every
  /// backend. Slow: not part of a step's time.
  PenetrationReport probePenetration() const;

  btCollisionWorld& collisionWorld();
  /// The dynamics world, or nullptr when the scene does not ask for dynamics.
  btDiscreteDynamicsWorld* dynamicsWorld();

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
};

}  // namespace adb::scene
