// Internal: an assimp scene checked before anything processes it. assimp's readers can leave
// faces with no indices, indices past the vertices or null arrays in a scene built from a
// damaged file, and its triangulation asserts (aborting the process) or reads out of bounds
// on them. Checked here first, every fault a MeshFileError naming the file, mesh and face.
#pragma once

#include <string>

#include "adb/io/mesh_file.h"

struct aiScene;

namespace adb::io::detail {

void checkBeforeTriangulation(const aiScene& scene, const std::string& file,
                              const LoadLimits& limits);

}  // namespace adb::io::detail
