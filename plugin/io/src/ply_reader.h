// Internal: PLY files (ascii, binary little and big endian) read by adb, not assimp. assimp
// 5.2's PLY reader trusts the file: a header cut short makes it loop forever, declared counts
// make it allocate for them, and damaged bodies make it read out of bounds (fuzzing found
// all three). This reader checks every count against the bytes left before it reserves
// anything, and every value as it reads it.
#pragma once

#include <cstddef>
#include <string>

#include "polygon_mesh.h"

namespace adb::io::detail {

/// Whether the data starts like a PLY file ("ply" and a line end).
bool looksLikePly(const char* data, std::size_t size);

/// Vertices (the x, y, z properties of element "vertex") and faces (the first list property
/// of element "face", vertex_indices by convention); other elements and properties are read
/// past. Throws MeshFileError naming `name`, the element and its index.
PolygonMesh readPly(const char* data, std::size_t size, const std::string& name,
                    const LoadLimits& limits);

}  // namespace adb::io::detail
