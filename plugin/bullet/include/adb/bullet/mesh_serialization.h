// Reading MeshShapes back from what Bullet's btDefaultSerializer wrote.
//
// MeshShape::serialize writes its mesh as Bullet's own btTriangleMeshShapeData, so a saved
// world keeps its meshes: Bullet's btBulletWorldImporter (libbullet-extras) reads them as
// btBvhTriangleMeshShapes, and loadMeshShapes here reads them as MeshShapes, without
// depending on Bullet's extras.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "adb/bullet/mesh_shape.h"
#include "adb/bullet/precision.h"

namespace adb {

/// One shape read back by loadMeshShapes.
struct LoadedMeshShape {
  std::unique_ptr<MeshShape> shape;
  /// The name registered for the shape with btSerializer::registerNameForPointer, or empty.
  std::string name;
};

/// Every triangle-mesh shape in `buffer` (btSerializer::getBufferPointer() and
/// getCurrentBufferSize(), or a .bullet file's bytes), in the order they were written: what
/// MeshShape::serialize wrote, and btBvhTriangleMeshShape's too (all its parts concatenated).
/// Each shape gets the same vertices, triangles, local scaling and margin; its tree is rebuilt
/// with `settings` (trees are not stored), in the frame the vertices were written in
/// (meshFromShape is not stored: it is the identity on load). Shapes whose meshes are equal
/// share one MeshData, as they usually did when written. Other shapes (compounds, convex
/// shapes, ...) are skipped, but a MeshShape inside a compound is read like the others.
///
/// Reads buffers of either Bullet precision written by a machine with this one's pointer size
/// and byte order (the format stores structs as laid out in memory; Bullet's importer
/// converts others). Throws MeshError naming the problem for anything else, for a truncated or
/// malformed buffer and for an invalid mesh; SettingsError for bad `settings`.
std::vector<LoadedMeshShape> loadMeshShapes(const void* buffer, std::size_t size,
                                            const BuildSettings& settings = {});

}  // namespace adb
