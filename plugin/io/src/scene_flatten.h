// flattenScene: an assimp scene as one vertex/triangle list. The scene graph is walked from the
// root, each node's meshes are placed by the node's global transform (accumulated in double),
// positions are welded per mesh instance (exactly equal ones only), and point and line
// primitives are counted and skipped. Nothing is validated here that the core validates
// (finite coordinates): this only guards what would otherwise be read out of bounds.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "adb/core/mesh.h"

struct aiScene;

namespace adb::io::detail {

/// One placement of an assimp mesh by a node. Its vertices are FlatScene::vertices from
/// firstVertex up to the next instance's firstVertex.
struct MeshInstance {
  unsigned mesh = 0;  ///< index into aiScene::mMeshes
  std::string node;   ///< path of the node from the root, e.g. "ROOT/arm/hand"
  std::uint32_t firstVertex = 0;
};

struct FlatScene {
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;
  std::vector<std::uint32_t> sourceVertex;  ///< per vertex: its index in its assimp mesh
  std::vector<MeshInstance> instances;      ///< those that gave triangles, in vertex order
  std::size_t skippedPoints = 0;            ///< point primitives (not a collision surface)
  std::size_t skippedLines = 0;             ///< line primitives
  std::size_t instancesWithoutTriangles = 0;  ///< mesh instances of points/lines only
  std::vector<unsigned> unreferencedMeshes;   ///< meshes no node places (not loaded)
};

/// Throws MeshFileError (naming `file`) for what assimp should not have produced but may: a
/// node placing a mesh that does not exist, a face index out of range, a polygon left after
/// triangulation, a node reached twice, more vertices than 32-bit indices hold.
FlatScene flattenScene(const aiScene& scene, const std::string& file);

/// Where merged vertex v came from, e.g. "vertex 3 of assimp mesh 0 'cube' placed by node
/// 'ROOT/cube', at (nan, 0, 0) in the mesh's own coordinates".
std::string describeVertexOrigin(const aiScene& scene, const FlatScene& flat, std::size_t v);

}  // namespace adb::io::detail
