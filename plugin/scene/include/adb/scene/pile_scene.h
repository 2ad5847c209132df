// A pile as scene data: concave bodies dropped into a bin, the scene adb-demo runs without
// --scene and the budget sweep measures. Generated bodies (tori, gears, torus knots) or copies
// of mesh files; a bin of box meshes, of btBoxShape walls, or a plane floor between them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "adb/scene/scene.h"

namespace adb::scene {

struct PileSpec {
  /// What the bin is made of.
  enum class Floor {
    Mesh,   ///< floor and walls as box meshes (adb's MeshShape; Bullet's BVH for the peers)
    Box,    ///< floor and walls as btBoxShape, the way Bullet users build bins
    Plane,  ///< floor a btStaticPlaneShape (y = 0), walls as btBoxShape
  };
  int bodies = 24;
  std::size_t trianglesPerBody = 1500;  ///< approximate, per generated body
  std::uint64_t seed = 1;               ///< of the bodies' starting poses
  Floor floor = Floor::Mesh;
  /// Non-empty: the bodies are copies of these files (cycled through), each scaled to 0.8
  /// across; trianglesPerBody is then ignored.
  std::vector<std::filesystem::path> meshes;
  /// Non-empty (and no meshes): every body is this generated model (adb::makeModel's
  /// names: pipes, gears, knot, ...) at trianglesPerBody, scaled to 0.8 across. Empty: tori,
  /// gears and knots in turn.
  std::string model;
  /// Bullet's deactivation: bodies at rest fall asleep, as Bullet users have it.
  bool sleeping = true;
  int steps = 300;
};

/// The pile: the bin's floor top at y = 0, its inside 5 x 5 (world.bounds: a body out of it
/// is lost), bodies on a 3 x 3 grid per layer 0.9 apart from 1 above the floor, turned at
/// random; friction 0.6, Bullet's sleeping (unless spec.sleeping is false), plausible contacts
/// softened. Throws std::invalid_argument
/// for a non-positive body count.
Scene makePileScene(const PileSpec& spec);

}  // namespace adb::scene
