// Internal: assimp's readers run in a child process. Fuzzing found assimp 5.2's glTF reader
// reading past a buffer and its 3MF reader dying on a signal on damaged files, inside
// ReadFile, where nothing of ours can check first; a reader may also loop or allocate without
// bound. A child that crashes, runs past LoadLimits::maxReadSeconds or its memory limit takes
// only itself down: the caller gets one MeshFileError and goes on. The child sends the mesh
// (or the error) back through a pipe.
#pragma once

#include <functional>
#include <string>
#include <utility>

#include "adb/core/mesh.h"
#include "adb/io/mesh_file.h"

namespace adb::io::detail {

/// The result `read` gives in a child process, or its MeshFileError; throws MeshFileError
/// naming `name` when the child crashes, times out or runs out of memory.
adb::TriangleMesh readIsolated(const std::function<std::pair<adb::TriangleMesh, LoadReport>()>& read,
                               const std::string& name, LoadReport* report,
                               const LoadLimits& limits);

}  // namespace adb::io::detail
