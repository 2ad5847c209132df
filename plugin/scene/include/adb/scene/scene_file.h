// Reading scene files (JSON; the schema: docs/scenes.md and docs/scene.schema.json).
#pragma once

#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "adb/scene/scene.h"

namespace adb::scene {

/// One clear error for a bad scene: the file, where in it (a JSON path such as
/// `bodies[3].shape`, or line and column for a syntax error) and what is wrong.
class SceneError : public std::runtime_error {
 public:
  SceneError(std::string file, std::string where, const std::string& what);
  const std::string& file() const { return m_file; }
  /// The JSON path (`bodies[3].shape`) or `line L, column C`; empty for the whole file.
  const std::string& where() const { return m_where; }

 private:
  std::string m_file;
  std::string m_where;
};

/// Reads and validates a scene file. Mesh files are resolved against the scene file's folder
/// and must exist (they are read when the scene is built). Throws SceneError.
Scene loadScene(const std::filesystem::path& file);

/// Meshes given in code, by the name of the mesh shape that takes one.
using GivenMeshes = std::map<std::string, std::shared_ptr<const TriangleMesh>>;

/// The same from text; `name` stands for the file in errors, `folder` resolves mesh files.
/// A shape of type "mesh" without a "file" takes the mesh `meshes` holds under its name (a
/// scene built in code, or in Python).
Scene parseScene(const std::string& text, const std::string& name,
                 const std::filesystem::path& folder = {}, const GivenMeshes& meshes = {});

}  // namespace adb::scene
