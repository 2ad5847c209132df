// Internal: what adb's own readers (PLY, OFF) produce: positions and polygons, before they
// become one validated TriangleMesh.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "adb/core/mesh.h"
#include "adb/io/mesh_file.h"

namespace adb::io::detail {

struct PolygonMesh {
  std::vector<Vec3> vertices;
  std::vector<std::uint32_t> corners;     ///< every face's vertex indices, one after another
  std::vector<std::uint32_t> faceSizes;   ///< corners per face
};

/// Polygons fanned into triangles (a face of 1 or 2 corners is a point or a line: counted and
/// skipped), indices checked, and the core's validation (finite coordinates, at least one
/// triangle). Throws MeshFileError naming `name` and, for an index, the face.
adb::TriangleMesh meshFromPolygons(PolygonMesh polygons, const std::string& name,
                                   LoadReport* report);

/// Reads the body of a text format: whitespace-separated tokens, `#` comments to the end of a
/// line (OFF). A token longer than 64 characters comes back cut and marked, not a number.
class TextTokens {
 public:
  TextTokens(const char* data, std::size_t size, std::size_t at, bool hashComments)
      : m_data(data), m_size(size), m_at(at), m_hashComments(hashComments) {}
  /// The next token, or false at the end.
  bool next(std::string& token);
  /// Skips to the start of the next line.
  void skipLine();
  std::size_t line() const { return m_line; }

 private:
  const char* m_data;
  std::size_t m_size, m_at;
  bool m_hashComments;
  std::size_t m_line = 1;
};

/// A token as a finite double or an index; false when it is not one.
bool parseNumber(const std::string& token, double& out);
bool parseIndex(const std::string& token, std::uint64_t& out);

}  // namespace adb::io::detail
