#include "scene_checks.h"

#include <assimp/scene.h>

#include <cstdint>

namespace adb::io::detail {
namespace {

[[noreturn]] void fail(const std::string& file, const std::string& what) {
  throw MeshFileError(file + ": " + what);
}

void checkNode(const aiScene& scene, const aiNode* node, const std::string& file, int depth) {
  if (node == nullptr) fail(file, "a node of the scene graph is missing");
  // Deeper than any real scene graph: a damaged file's cycle, or a stack about to overflow.
  if (depth > 1024) fail(file, "the scene graph is more than 1024 nodes deep");
  if (node->mNumMeshes > 0 && node->mMeshes == nullptr) fail(file, "a node's mesh list is missing");
  for (unsigned i = 0; i < node->mNumMeshes; ++i) {
    if (node->mMeshes[i] >= scene.mNumMeshes) {
      fail(file, "a node places mesh " + std::to_string(node->mMeshes[i]) + " of " +
                     std::to_string(scene.mNumMeshes));
    }
  }
  if (node->mNumChildren > 0 && node->mChildren == nullptr) fail(file, "a node's children are missing");
  for (unsigned i = 0; i < node->mNumChildren; ++i) checkNode(scene, node->mChildren[i], file, depth + 1);
}

// The primitive-type flag of a face with `corners` corners (assimp's own classification).
unsigned primitiveType(unsigned corners) {
  switch (corners) {
    case 1: return aiPrimitiveType_POINT;
    case 2: return aiPrimitiveType_LINE;
    case 3: return aiPrimitiveType_TRIANGLE;
    default: return aiPrimitiveType_POLYGON;
  }
}

void checkMesh(aiMesh& mesh, unsigned m, const std::string& file, const LoadLimits& limits,
               std::uint64_t& vertices, std::uint64_t& faces) {
  const std::string label = "mesh " + std::to_string(m);
  vertices += mesh.mNumVertices;
  faces += mesh.mNumFaces;
  if (vertices > limits.maxVertices) {
    fail(file, "more than " + std::to_string(limits.maxVertices) +
                   " vertices (LoadLimits::maxVertices)");
  }
  if (faces > limits.maxFaces) {
    fail(file, "more than " + std::to_string(limits.maxFaces) + " faces (LoadLimits::maxFaces)");
  }
  if (mesh.mNumVertices > 0 && mesh.mVertices == nullptr) fail(file, label + " has no positions");
  if (mesh.mNumFaces > 0 && mesh.mFaces == nullptr) fail(file, label + " has no faces array");
  unsigned types = 0;
  for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
    const aiFace& face = mesh.mFaces[f];
    // Built only for an error: a string per face would cost more than the check.
    const auto where = [&] { return label + ", face " + std::to_string(f); };
    if (face.mNumIndices == 0 || face.mIndices == nullptr) fail(file, where() + " has no vertices");
    if (face.mNumIndices > limits.maxFaceCorners) {
      fail(file, where() + " has " + std::to_string(face.mNumIndices) + " corners, more than " +
                     std::to_string(limits.maxFaceCorners) + " (LoadLimits::maxFaceCorners)");
    }
    for (unsigned k = 0; k < face.mNumIndices; ++k) {
      if (face.mIndices[k] >= mesh.mNumVertices) {
        fail(file, where() + " references vertex " + std::to_string(face.mIndices[k]) +
                       ", but the mesh has " + std::to_string(mesh.mNumVertices) + " vertices");
      }
    }
    types |= primitiveType(face.mNumIndices);
  }
  mesh.mPrimitiveTypes |= types;
}

}  // namespace

void checkBeforeTriangulation(aiScene& scene, const std::string& file, const LoadLimits& limits) {
  if (scene.mNumMeshes > 0 && scene.mMeshes == nullptr) fail(file, "the mesh list is missing");
  std::uint64_t vertices = 0, faces = 0;
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    if (scene.mMeshes[m] == nullptr) fail(file, "mesh " + std::to_string(m) + " is missing");
    checkMesh(*scene.mMeshes[m], m, file, limits, vertices, faces);
  }
  checkNode(scene, scene.mRootNode, file, 0);
}

}  // namespace adb::io::detail
