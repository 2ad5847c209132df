// loadMesh: file checks, assimp's import (logs captured), flattening, the core's validation.
#include "adb/io/mesh_file.h"

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <system_error>

#include "assimp_log_capture.h"
#include "scene_flatten.h"

namespace adb::io {
namespace {

namespace fs = std::filesystem;

// Triangulate only. Not JoinIdenticalVertices (it merges positions up to 1e-5 apart and, given
// a NaN, merges other vertices into it; flattenScene welds exactly instead), not
// FindInvalidData (it deletes a mesh with a NaN position, the file would then "load" without
// it), not ValidateDataStructure (it leaves NaN alone, and flattenScene checks the indices and
// node references it would, naming the file, mesh and face). Nothing else is needed: only
// positions are read.
constexpr unsigned kPostProcess = aiProcess_Triangulate;

// Before assimp: its own answer for a missing or unreadable file is "Unable to open file".
void checkReadable(const std::string& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (!fs::exists(status)) throw MeshFileError(path + ": no such file");
  if (fs::is_directory(status)) throw MeshFileError(path + ": is a directory, not a mesh file");
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    throw MeshFileError(path + ": cannot be opened for reading (" + std::strerror(errno) + ")");
  }
  if (in.peek() == std::ifstream::traits_type::eof()) {
    throw MeshFileError(path + ": the file is empty");
  }
}

}  // namespace

adb::TriangleMesh loadMesh(const std::string& path, LoadReport* report) {
  checkReadable(path);

  std::vector<std::string> warnings;
  std::unique_ptr<aiScene> scene;
  {
    detail::AssimpLogCapture capture;  // one load at a time: see assimp_log_capture.h
    Assimp::Importer importer;
    // A file with bones but no meshes would otherwise get a generated skeleton mesh: triangles
    // the file does not have.
    importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
    const aiScene* read = importer.ReadFile(path, kPostProcess);
    for (std::string& line : capture.take()) warnings.push_back(path + ": " + std::move(line));
    if (read == nullptr) {
      throw MeshFileError(path + ": assimp cannot read it: " + importer.GetErrorString());
    }
    scene.reset(importer.GetOrphanedScene());  // ours now: processed outside the lock
  }

  detail::FlatScene flat = detail::flattenScene(*scene, path);
  if (flat.skippedPoints + flat.skippedLines > 0) {
    warnings.push_back(path + ": skipped " + std::to_string(flat.skippedPoints) +
                       " point and " + std::to_string(flat.skippedLines) +
                       " line primitives (not a surface)");
  }
  for (unsigned m : flat.unreferencedMeshes) {
    warnings.push_back(path + ": assimp mesh " + std::to_string(m) +
                       " is placed by no node of the scene graph: not loaded");
  }
  if (flat.triangles.empty()) {
    const unsigned meshes = scene->mNumMeshes;
    throw MeshFileError(path + ": no triangles (" + std::to_string(flat.skippedPoints) +
                        " point and " + std::to_string(flat.skippedLines) +
                        " line primitives in " + std::to_string(meshes) +
                        (meshes == 1 ? " assimp mesh)" : " assimp meshes)"));
  }

  // The core validates (and names the merged vertex); we only remember where the first
  // non-finite vertex came from, to add that to its message. The core checks vertices in order,
  // so that is the one it names.
  std::size_t firstNonFinite = flat.vertices.size();
  for (std::size_t v = 0; v < flat.vertices.size(); ++v) {
    if (!flat.vertices[v].allFinite()) {
      firstNonFinite = v;
      break;
    }
  }
  std::optional<adb::TriangleMesh> mesh;
  try {
    mesh.emplace(std::move(flat.vertices), std::move(flat.triangles), path);
  } catch (const adb::MeshError& e) {
    std::string what = e.what();
    if (firstNonFinite < flat.sourceVertex.size()) {
      what += " (" + detail::describeVertexOrigin(*scene, flat, firstNonFinite) + ")";
    }
    throw MeshFileError(what);
  }

  if (report != nullptr) {
    report->warnings = std::move(warnings);
    report->sourceMeshes = flat.instances.size();
    report->triangles = mesh->triangleCount();
    report->vertices = mesh->vertices().size();
  }
  return std::move(*mesh);
}

}  // namespace adb::io
