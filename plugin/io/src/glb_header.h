// Internal: a GLB's declared lengths checked against the file before assimp's glTF readers see
// them. They allocate, and zero, the JSON chunk's declared length before they read it: one
// damaged length (3.4 GB in a 217 kB file) took 0.9 to 7.4 s and 3.3 GB of memory per load
// before this check (the command is in docs/reliability.md, "Mutated real meshes").
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace adb::io::detail {

/// When the data starts with GLB's magic "glTF": throws a MeshFileError naming `name` if the
/// header is cut short, or if the total length or a chunk's length that the header declares
/// runs past the end of the data. Other data passes unread.
void checkGlbBytes(const char* data, std::size_t size, const std::string& name);

/// The same for the file at `path`, `fileBytes` long: reads only its headers.
void checkGlbFile(const std::string& path, std::uint64_t fileBytes);

}  // namespace adb::io::detail
