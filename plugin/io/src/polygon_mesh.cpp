#include "polygon_mesh.h"

#include <cctype>
#include <cerrno>
#include <cstdlib>

namespace adb::io::detail {

adb::TriangleMesh meshFromPolygons(PolygonMesh p, const std::string& name, LoadReport* report) {
  std::vector<Triangle> triangles;
  std::size_t points = 0, lines = 0, at = 0;
  const std::size_t vertices = p.vertices.size();
  for (std::size_t f = 0; f < p.faceSizes.size(); ++f) {
    const std::uint32_t n = p.faceSizes[f];
    const std::uint32_t* c = p.corners.data() + at;  // no element when the face has none
    at += n;
    for (std::uint32_t k = 0; k < n; ++k) {
      if (c[k] >= vertices) {
        throw MeshFileError(name + ": face " + std::to_string(f) + " references vertex " +
                            std::to_string(c[k]) + ", but the mesh has " +
                            std::to_string(vertices) + " vertices");
      }
    }
    if (n == 1) ++points;
    if (n == 2) ++lines;
    // A fan: exact for the convex polygons these formats hold in practice (quads, mostly).
    for (std::uint32_t k = 2; k < n; ++k) triangles.push_back({c[0], c[k - 1], c[k]});
  }
  if (triangles.empty()) {
    throw MeshFileError(name + ": no triangles (" + std::to_string(p.faceSizes.size()) +
                        " faces: " + std::to_string(points) + " points, " +
                        std::to_string(lines) + " lines)");
  }
  std::vector<std::string> warnings;
  if (points + lines > 0) {
    warnings.push_back(name + ": skipped " + std::to_string(points) + " point and " +
                       std::to_string(lines) + " line primitives (not a surface)");
  }
  try {
    adb::TriangleMesh mesh(std::move(p.vertices), std::move(triangles), name);
    if (report) {
      report->warnings = std::move(warnings);
      report->sourceMeshes = 1;
      report->triangles = mesh.triangleCount();
      report->vertices = mesh.vertices().size();
    }
    return mesh;
  } catch (const adb::MeshError& e) {
    throw MeshFileError(e.what());
  }
}

bool TextTokens::next(std::string& token) {
  token.clear();
  while (m_at < m_size) {
    const char c = m_data[m_at];
    if (c == '\n') ++m_line;
    if (m_hashComments && c == '#') {
      skipLine();
      continue;
    }
    if (!std::isspace(static_cast<unsigned char>(c))) break;
    ++m_at;
  }
  while (m_at < m_size && !std::isspace(static_cast<unsigned char>(m_data[m_at])) &&
         !(m_hashComments && m_data[m_at] == '#')) {
    // No number is longer: the token is kept short and marked, so that it parses as nothing.
    if (token.size() < 64) {
      token += m_data[m_at];
    } else {
      token.back() = '?';
    }
    ++m_at;
  }
  return !token.empty();
}

void TextTokens::skipLine() {
  while (m_at < m_size && m_data[m_at] != '\n') ++m_at;
  if (m_at < m_size) {
    ++m_at;
    ++m_line;
  }
}

bool parseNumber(const std::string& token, double& out) {
  if (token.empty()) return false;
  char* end = nullptr;
  errno = 0;
  out = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size();  // NaN and inf parse: the core names them
}

bool parseIndex(const std::string& token, std::uint64_t& out) {
  if (token.empty() || token.size() > 19 ||
      token.find_first_not_of("0123456789") != std::string::npos) {
    return false;
  }
  out = std::stoull(token);
  return true;
}

}  // namespace adb::io::detail
