// The demo's scene: generated concave bodies (tori, gears, torus knots), or copies of a given
// mesh, dropped into a bin, simulated in a btDiscreteDynamicsWorld with adb's MeshShape,
// Bullet's GImpact, or a convex decomposition of each mesh (Bullet's HACD, hulls in a
// btCompoundShape), on the same meshes, poses, masses, bin and time step. The bin's floor and
// walls are triangle meshes, Bullet boxes, or a plane floor between box walls.
#pragma once

#include <btBulletDynamicsCommon.h>

#include <memory>
#include <string>
#include <vector>

#include "adb/bullet/frame_budget.h"
#include "adb/core/mesh.h"

namespace adb::demo {

enum class Backend {
  Adb,
  GImpact,
  Convex,  ///< each mesh decomposed into convex hulls (convex_decomposition.h)
};

/// What the convex backend prepared before the first step.
struct DecompositionReport {
  std::vector<std::size_t> hullsPerKind;  ///< per distinct mesh
  /// Per distinct mesh, the hulls' summed volume over the mesh's (0 when the mesh is not
  /// closed and has no volume): how much the hulls fill that the body does not.
  std::vector<double> volumeRatio;
  std::size_t hulls = 0;                  ///< over the distinct meshes
  double seconds = 0.0;                   ///< the decompositions' wall clock, all meshes
};

/// What the bin is made of (the same for every backend).
enum class Floor {
  Mesh,   ///< floor and walls as box meshes (MeshShape, else btBvhTriangleMeshShape)
  Box,    ///< floor and walls as btBoxShape, the way Bullet users build bins
  Plane,  ///< floor a btStaticPlaneShape (y = 0), walls as btBoxShape
};

struct SceneSettings {
  Backend backend = Backend::Adb;
  int bodies = 24;
  std::size_t trianglesPerBody = 1500;  ///< approximate, per generated body
  std::uint64_t seed = 1;
  Floor floor = Floor::Mesh;
  /// Non-empty: the bodies' meshes (cycled through), in place of the generated ones; each is
  /// scaled to 0.8 across its largest extent and moved to its principal frame;
  /// trianglesPerBody is then ignored.
  std::vector<TriangleMesh> meshes;
  FrameSettings frame;  ///< adb's per-step budget and quality knobs (adb backend)
};

/// Per-step figures of the world.
struct StepStats {
  double seconds = 0;         ///< wall clock of stepSimulation
  int contacts = 0;           ///< points in all manifolds
  double maxPenetration = 0;  ///< deepest contact, >= 0
  double bodyPenetration = 0; ///< deepest contact between two dynamic bodies, >= 0
  double binPenetration = 0;  ///< deepest contact between a body and the floor or a wall, >= 0
  /// Deepest vertex below the floor's top (y = 0), from the bodies' transforms and mesh
  /// vertices, whatever the contacts say; >= 0. And the same over each body's size (its
  /// bounding-box diagonal), the worst body.
  double floorPenetration = 0;
  double floorPenetrationRelative = 0;
  double kinetic = 0;         ///< translational + rotational kinetic energy
  double energy = 0;          ///< kinetic + potential (g = 9.81, height above the bin floor)
  int atRest = 0;             ///< bodies slower than 0.05 m/s and 0.05 rad/s
  double lowestY = 0;         ///< lowest body centre: below the floor means fell through
  int lost = 0;  ///< bodies whose centre left the bin (a quarter of their size below the floor, past a wall)
  /// Body-body penetration from the geometry (penetration_probe.h), the same measure for
  /// every backend: deepest vertex inside another body, and that over the body's size.
  /// Negative when the step was not probed (PileScene::probe).
  double probedDepth = -1;
  double probedRelative = -1;
  double probedMean = -1;  ///< each body's deepest penetration, averaged over the bodies
  FrameStats frame;           ///< adb backend: what the step did with its mesh-mesh pairs
};

class PileScene {
 public:
  explicit PileScene(const SceneSettings& settings);
  ~PileScene();
  PileScene(const PileScene&) = delete;
  PileScene& operator=(const PileScene&) = delete;

  /// Advances one fixed step of 1/60 s and measures it.
  StepStats step();
  /// Measures body-body penetration from the geometry into `stats` (slow: not part of the
  /// step's time).
  void probe(StepStats& stats) const;
  int bodyCount() const { return static_cast<int>(m_dynamic.size()); }
  /// The convex backend's decomposition (empty for the others).
  const DecompositionReport& decomposition() const { return m_decomposition; }
  std::size_t triangleCount() const { return m_triangles; }

 private:
  struct Impl;
  std::unique_ptr<Impl> m_impl;
  std::vector<btRigidBody*> m_dynamic;
  std::size_t m_triangles = 0;
  DecompositionReport m_decomposition;
};

}  // namespace adb::demo
