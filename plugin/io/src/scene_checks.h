// Internal: an assimp scene checked before anything processes it. assimp's readers can leave
// faces with no indices, indices past the vertices or null arrays in a scene built from a
// damaged file, and its triangulation asserts (aborting the process) or reads out of bounds
// on them. Checked here first, every fault a MeshFileError naming the file, mesh and face.
//
// One fault is mended instead: a mesh whose primitive-type flags miss a kind of face it holds.
// assimp's OBJ reader files a two-corner face ("f 1 2", a line) under polygons, and its
// validation then refuses the whole file; with the flag set, the line is skipped with a warning
// like any other line (scene_flatten.h).
#pragma once

#include <string>

#include "adb/io/mesh_file.h"

struct aiScene;

namespace adb::io::detail {

/// `scene` is the importer's, before any post-processing: only primitive-type flags change.
void checkBeforeTriangulation(aiScene& scene, const std::string& file, const LoadLimits& limits);

}  // namespace adb::io::detail
