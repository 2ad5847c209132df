// Internal: the element counts a PLY or OFF header declares, checked against the file's size
// and the load limits before assimp reads a byte of the body. assimp's readers trust the
// header: a header that declares a billion vertices in a 1 kB file makes them allocate (or
// loop) for the billion, and a header cut short before `end_header` makes its PLY reader loop
// forever.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "adb/io/mesh_file.h"

namespace adb::io::detail {

/// Bytes of a file's start that checkDeclaredCounts needs at most (a PLY header longer than
/// this is refused: no real one comes near it).
constexpr std::size_t kHeaderBytes = 64 * 1024;

/// `head` is the start of the data (up to kHeaderBytes), `size` the whole size. Does nothing
/// for formats other than PLY and OFF; throws MeshFileError naming `name` for a header that
/// cannot be read or declares more than the file could hold or the limits allow.
void checkDeclaredCounts(const char* head, std::size_t headSize, std::uint64_t size,
                         const std::string& name, const LoadLimits& limits);

}  // namespace adb::io::detail
