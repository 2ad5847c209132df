// Internal: OFF files read by adb, not assimp. assimp 5.2's OFF reader takes a face's
// declared corner count and indices on trust and reads out of bounds on a damaged file
// (fuzzing found it). This reader checks the counts against the bytes left before reserving,
// and every index as it reads it.
#pragma once

#include <cstddef>
#include <string>

#include "polygon_mesh.h"

namespace adb::io::detail {

/// Whether the data starts like an OFF file: a first word OFF, COFF, NOFF, CNOFF, STOFF, ...
bool looksLikeOff(const char* data, std::size_t size);

/// Ascii OFF with 3D vertices: each vertex line's first three numbers are its position (the
/// colour, normal or texture coordinates the prefixes announce are read past), each face
/// line a corner count and that many indices (a colour after them is read past).
PolygonMesh readOff(const char* data, std::size_t size, const std::string& name,
                    const LoadLimits& limits);

}  // namespace adb::io::detail
