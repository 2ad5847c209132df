// loadMesh: file checks, assimp's import (logs captured), flattening, the core's validation.
#include "adb/io/mesh_file.h"
#include "adb/io/message_text.h"

#include <assimp/Importer.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <iterator>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <system_error>

#include "ascii_case.h"
#include "assimp_log_capture.h"
#include "glb_header.h"
#include "isolated_read.h"
#include "off_reader.h"
#include "ply_reader.h"
#include "polygon_mesh.h"
#include "reader_choice.h"
#include "scene_checks.h"
#include "scene_flatten.h"

namespace adb::io {
namespace {

namespace fs = std::filesystem;

// Read with no post-processing, then, once checked: assimp's ValidateDataStructure and
// Triangulate, nothing else. Not JoinIdenticalVertices (it merges positions up to 1e-5 apart
// and, given a NaN, merges other vertices into it; flattenScene welds exactly instead), not
// FindInvalidData (it deletes a mesh with a NaN position, the file would then "load" without
// it). Only positions are read.
constexpr unsigned kReadAsIs = 0;

// Before assimp: its own answer for a missing or unreadable file is "Unable to open file".
// Throws unless `path` is a readable, non-empty file within the limits; returns its size.
std::uint64_t checkReadable(const std::string& path, const LoadLimits& limits) {
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
  const std::uint64_t size = fs::file_size(path, ec);
  if (size > limits.maxFileBytes) {
    throw MeshFileError(path + ": " + std::to_string(size) + " bytes, more than the limit of " +
                        std::to_string(limits.maxFileBytes) + " (LoadLimits::maxFileBytes)");
  }
  return size;
}

// assimp's scene, read by `read` (with no post-processing), checked, validated and
// triangulated; its log lines go to `warnings`.
template <class Read>
std::unique_ptr<aiScene> importScene(Read read, const std::string& name, const LoadLimits& limits,
                                     std::vector<std::string>& warnings) {
  detail::AssimpLogCapture capture;  // one load at a time: see assimp_log_capture.h
  Assimp::Importer importer;
  // A file with bones but no meshes would otherwise get a generated skeleton mesh: triangles
  // the file does not have.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  auto logged = [&] {
    for (std::string& line : capture.take()) warnings.push_back(name + ": " + std::move(line));
  };
  const aiScene* scene = read(importer);
  logged();
  if (scene == nullptr) {
    throw MeshFileError(name + ": assimp cannot read it: " + excerpt(importer.GetErrorString()));
  }
  // assimp's validation would call this "invalid": to a user it is a file with no triangles.
  if (scene->mNumMeshes == 0) throw MeshFileError(name + ": no triangles (no mesh in the file)");
  // The importer hands out its scene as const; before its post-processing it is ours to mend
  // as assimp's own steps do (scene_checks.h: only primitive-type flags).
  detail::checkBeforeTriangulation(const_cast<aiScene&>(*scene), name, limits);
  for (const unsigned step : {unsigned(aiProcess_ValidateDataStructure), unsigned(aiProcess_Triangulate)}) {
    scene = importer.ApplyPostProcessing(step);
    logged();
    if (scene == nullptr) {
      throw MeshFileError(name + ": not a valid mesh: " + excerpt(importer.GetErrorString()));
    }
  }
  return std::unique_ptr<aiScene>(importer.GetOrphanedScene());  // processed outside the lock
}

adb::TriangleMesh meshOf(std::unique_ptr<aiScene> scene, std::vector<std::string> warnings,
                         const std::string& path, LoadReport* report);

// A mesh through assimp: read by `read`, checked, triangulated, flattened and validated, in a
// child process unless the limits say otherwise (isolated_read.h says why).
template <class Read>
adb::TriangleMesh assimpMesh(Read read, const std::string& name, LoadReport* report,
                             const LoadLimits& limits) {
  auto load = [&] {
    std::vector<std::string> warnings;
    std::unique_ptr<aiScene> scene = importScene(read, name, limits, warnings);
    LoadReport r;
    adb::TriangleMesh mesh = meshOf(std::move(scene), std::move(warnings), name, &r);
    return std::make_pair(std::move(mesh), std::move(r));
  };
  if (limits.isolate) return detail::readIsolated(load, name, report, limits);
  auto loaded = load();
  if (report) *report = std::move(loaded.second);
  return std::move(loaded.first);
}

// Whether assimp reads files with this extension (lower case, no dot): asked once.
bool assimpExtension(const std::string& extension) {
  static const std::string list = [] {
    std::string l;
    Assimp::Importer().GetExtensionList(l);  // "*.3ds;*.obj;..."
    return ";" + detail::lowered(l) + ";";
  }();
  return !extension.empty() && list.find(";*." + extension + ";") != std::string::npos;
}

enum class OwnFormat { None, Ply, Off };

// Which of adb's own readers takes the data. assimp picks its reader by the extension, and
// for an extension it does not know by searching the first 200 bytes for a format's word: a
// file with "ply" or "off" there would reach assimp's PLY or OFF reader (ply_reader.h and
// off_reader.h say why those must not read a file from anywhere), so such data is ours.
OwnFormat ownFormat(const char* data, std::size_t size, const std::string& extension) {
  if (extension == "ply") return OwnFormat::Ply;
  if (extension == "off") return OwnFormat::Off;
  if (assimpExtension(extension)) return OwnFormat::None;
  if (detail::looksLikePly(data, size)) return OwnFormat::Ply;
  if (detail::looksLikeOff(data, size)) return OwnFormat::Off;
  const std::string head = detail::lowered(std::string(data, std::min<std::size_t>(size, 200)));
  if (head.find("ply") != std::string::npos) return OwnFormat::Ply;
  if (head.find("off") != std::string::npos) return OwnFormat::Off;
  return OwnFormat::None;
}

adb::TriangleMesh readOwnFormat(OwnFormat format, const char* data, std::size_t size,
                                const std::string& name, LoadReport* report,
                                const LoadLimits& limits) {
  detail::PolygonMesh polygons = format == OwnFormat::Ply ? detail::readPly(data, size, name, limits)
                                                          : detail::readOff(data, size, name, limits);
  return detail::meshFromPolygons(std::move(polygons), name, report);
}

// Data that may reach assimp's glTF readers: under their extensions, or under one no reader
// claims (assimp then asks every reader, glTF's among them).
bool mayBeGlb(const std::string& extension) {
  return extension == "gltf" || extension == "glb" || !assimpExtension(extension);
}

std::string lowerExtension(const std::string& path) {
  std::string e = fs::path(path).extension().string();
  if (!e.empty()) e.erase(0, 1);
  return detail::lowered(e);
}

// The whole file, for adb's own readers (its size is within the limits).
std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.eof() && in.fail()) throw MeshFileError(path + ": read failed");
  return bytes;
}

std::string head(const std::string& path) {
  std::string bytes(200, '\0');
  std::ifstream in(path, std::ios::binary);
  in.read(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  return bytes;
}

}  // namespace

adb::TriangleMesh loadMesh(const std::string& path, LoadReport* report, const LoadLimits& limits) {
  const std::uint64_t size = checkReadable(path, limits);
  const std::string start = head(path);
  const std::string extension = lowerExtension(path);
  const OwnFormat own = ownFormat(start.data(), start.size(), extension);
  if (own != OwnFormat::None) {
    const std::string bytes = contents(path);
    return readOwnFormat(own, bytes.data(), bytes.size(), path, report, limits);
  }
  if (mayBeGlb(extension)) detail::checkGlbFile(path, size);
  return assimpMesh(
      [&](Assimp::Importer& importer) {
        detail::requireReaderForExtension(importer, path, *importer.GetIOHandler(), path);
        return importer.ReadFile(path, kReadAsIs);
      },
      path, report, limits);
}

adb::TriangleMesh loadMeshFromMemory(const void* data, std::size_t size,
                                     const std::string& formatHint, const std::string& name,
                                     LoadReport* report, const LoadLimits& limits) {
  if (data == nullptr || size == 0) throw MeshFileError(name + ": no data");
  if (size > limits.maxFileBytes) {
    throw MeshFileError(name + ": " + std::to_string(size) + " bytes, more than the limit of " +
                        std::to_string(limits.maxFileBytes) + " (LoadLimits::maxFileBytes)");
  }
  const std::string hint = detail::lowered(formatHint);
  const char* bytes = static_cast<const char*>(data);
  const OwnFormat own = ownFormat(bytes, size, hint);
  if (own != OwnFormat::None) return readOwnFormat(own, bytes, size, name, report, limits);
  if (mayBeGlb(hint)) detail::checkGlbBytes(bytes, size, name);
  return assimpMesh(
      [&](Assimp::Importer& importer) {
        // The name and I/O system that ReadFileFromMemory gives assimp's readers.
        Assimp::MemoryIOSystem io(static_cast<const std::uint8_t*>(data), size,
                                  importer.GetIOHandler());
        detail::requireReaderForExtension(
            importer, std::string(AI_MEMORYIO_MAGIC_FILENAME) + "." + formatHint, io, name);
        return importer.ReadFileFromMemory(data, size, kReadAsIs, formatHint.c_str());
      },
      name, report, limits);
}

namespace {

// The checked scene flattened into one mesh, validated by the core.
adb::TriangleMesh meshOf(std::unique_ptr<aiScene> scene, std::vector<std::string> warnings,
                         const std::string& path, LoadReport* report) {
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

}  // namespace

}  // namespace adb::io
