// Mesh files: loadMesh reads any format assimp reads into one validated adb::TriangleMesh.
//
// The whole scene graph is flattened (node transforms applied, an instanced mesh once per
// instance), polygons are triangulated, and only positions are kept: a collision mesh needs
// nothing else. Nothing is repaired silently: bad data (NaN/infinite coordinates, out-of-range
// indices, no triangles) is an error, and what assimp only warns about (a missing material
// file, say) is handed back in LoadReport::warnings.
//
// Files come from anywhere, so nothing in them is trusted (docs/reliability.md):
// - PLY and OFF are read by adb: every count a header declares is checked against the bytes
//   left and the limits before anything is reserved, every value as it is read.
// - Every other format is read by assimp in a child process (LoadLimits::isolate): a reader
//   that crashes, loops or allocates without bound on a damaged file takes only the child down.
//   assimp reads with no post-processing; its scene is checked (every face's size and indices,
//   the node graph), validated (assimp's ValidateDataStructure) and only then triangulated.
// Every failure is one MeshFileError naming the file and what is wrong.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "adb/core/mesh.h"

namespace adb::io {

/// One error type for files: what() names the file and what is wrong (and where, e.g. the vertex).
class MeshFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What a load will take at most: a file beyond these gets a MeshFileError that names the
/// limit (raise it for files known to be that large).
struct LoadLimits {
  std::uint64_t maxFileBytes = std::uint64_t(4) << 30;  ///< 4 GiB
  std::uint64_t maxVertices = std::uint64_t(1) << 27;   ///< 134M, declared or read
  std::uint64_t maxFaces = std::uint64_t(1) << 27;      ///< 134M, declared or read
  std::uint32_t maxFaceCorners = 4096;  ///< a polygon's corners (triangulated: corners - 2)
  /// Formats read through assimp are read in a child process: a reader that crashes, loops
  /// or allocates without bound on a damaged file takes only the child down, and the load is
  /// one MeshFileError (docs/reliability.md). Off: read in this process (faster by a fork, for
  /// files known to be sound). PLY and OFF are read by adb, in this process, either way.
  bool isolate = true;
  double maxReadSeconds = 20.0;                           ///< the child's time (isolated)
  std::uint64_t maxReadBytes = std::uint64_t(16) << 30;   ///< the child's address space
};

/// What a successful load found besides the mesh.
struct LoadReport {
  /// assimp's warnings and errors during the load (e.g. a missing material / texture file:
  /// the mesh still loads) and ours (skipped point/line primitives, meshes no node uses).
  std::vector<std::string> warnings;
  std::size_t sourceMeshes = 0;  ///< assimp meshes merged, once per instance in the scene graph
  std::size_t triangles = 0;     ///< of the loaded mesh
  std::size_t vertices = 0;      ///< of the loaded mesh (positions welded per source mesh)
};

/// Reads any format assimp reads (OBJ, STL, PLY, glTF, OFF, ...), triangulates, applies every
/// node transform (the whole scene graph, instanced meshes counted once per instance), merges
/// into one adb::TriangleMesh (named by the file) validated by the core.
/// Throws MeshFileError for: missing/unreadable file, a file assimp cannot parse, a file with
/// no triangles (points/lines only or empty), NaN/inf coordinates (message names the file and
/// the vertex, re-wrapping the core's adb::MeshError), out-of-range indices.
/// Thread-safe: concurrent reads in this process are serialised (assimp's logger is one per
/// process; see src/assimp_log_capture.h); isolated reads run in their own processes, and an
/// application's own assimp logger hears only the reads made in this process.
adb::TriangleMesh loadMesh(const std::string& path, LoadReport* report = nullptr,
                           const LoadLimits& limits = {});

/// The same from bytes in memory: `formatHint` is the extension of the format ("ply", "obj",
/// "stl", "off", "gltf", "glb", "3mf", ...), `name` stands for the file in messages. A format
/// whose files refer to others (a glTF's .bin buffers) cannot read them from memory.
adb::TriangleMesh loadMeshFromMemory(const void* data, std::size_t size,
                                     const std::string& formatHint, const std::string& name,
                                     LoadReport* report = nullptr, const LoadLimits& limits = {});

}  // namespace adb::io
