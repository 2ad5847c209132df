// Internal: a GLB's declared lengths checked against the file before assimp's glTF readers see
// them. They allocate, and zero, the JSON chunk's declared length before they read it: one
// damaged length made them take 3.4 GB and 2.9 s over a 217 kB file
// (tests/fuzz/mutate_meshes.py), and a larger one runs into the reader's memory limit.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace adb::io::detail {

/// Reads `bytes` bytes at `offset` of the data into `out`; false if the data is shorter.
using ReadAt = std::function<bool(std::uint64_t offset, void* out, std::size_t bytes)>;

/// When the data (`fileBytes` long) starts with GLB's magic "glTF": throws a MeshFileError
/// naming `name` if the header is cut short, or if the total length or a chunk's length that
/// the header declares runs past the end of the file. Other data passes unread.
void checkGlbLengths(const ReadAt& readAt, std::uint64_t fileBytes, const std::string& name);

}  // namespace adb::io::detail
