// TriangleMesh validation: one pass over vertices, one over triangles.
#include "adb/core/mesh.h"

#include <cmath>
#include <sstream>

namespace adb {
namespace {

// A triangle is degenerate when twice its area is below this fraction of its longest edge
// squared: such a sliver has no usable normal in double precision.
constexpr double kDegenerateRelativeArea = 1e-12;

std::string describeVertex(const std::string& mesh, std::size_t i, const Vec3& v) {
  std::ostringstream os;
  os.precision(17);
  os << mesh << ": vertex " << i << " has a non-finite coordinate (" << v.x() << ", " << v.y()
     << ", " << v.z() << ")";
  return os.str();
}

}  // namespace

TriangleMesh::TriangleMesh(std::vector<Vec3> vertices, std::vector<Triangle> triangles,
                           std::string name)
    : m_vertices(std::move(vertices)), m_triangles(std::move(triangles)), m_name(std::move(name)) {
  if (m_triangles.empty()) {
    throw MeshError(m_name + ": the mesh has no triangles (" + std::to_string(m_vertices.size()) +
                    " vertices)");
  }
  if (m_triangles.size() >= (std::size_t{1} << 28)) {
    // The tree packs triangle indices into 28 bits (see tree.h).
    throw MeshError(m_name + ": " + std::to_string(m_triangles.size()) +
                    " triangles, more than the 268,435,455 a tree can index");
  }
  for (std::size_t i = 0; i < m_vertices.size(); ++i) {
    if (!m_vertices[i].allFinite()) throw MeshError(describeVertex(m_name, i, m_vertices[i]));
  }
  std::vector<bool> used(m_vertices.size(), false);
  for (std::size_t t = 0; t < m_triangles.size(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t v = m_triangles[t][k];
      if (v >= m_vertices.size()) {
        throw MeshError(m_name + ": triangle " + std::to_string(t) + " references vertex " +
                        std::to_string(v) + ", but the mesh has " +
                        std::to_string(m_vertices.size()) + " vertices");
      }
      used[v] = true;
      m_bounds.grow(m_vertices[v]);
    }
    if (isDegenerate(t)) {
      ++m_report.degenerateTriangles;
      const Triangle& tri = m_triangles[t];
      const Vec3 &a = m_vertices[tri[0]], &b = m_vertices[tri[1]], &c = m_vertices[tri[2]];
      if (a == b || b == c || a == c) ++m_report.repeatedVertexTriangles;
    }
  }
  for (bool u : used) m_report.unusedVertices += u ? 0 : 1;
}

double TriangleMesh::triangleArea(std::size_t i) const {
  const Triangle& t = m_triangles[i];
  const Vec3 &a = m_vertices[t[0]], &b = m_vertices[t[1]], &c = m_vertices[t[2]];
  return 0.5 * (b - a).cross(c - a).norm();
}

bool TriangleMesh::isDegenerate(std::size_t i) const {
  const Triangle& t = m_triangles[i];
  const Vec3 &a = m_vertices[t[0]], &b = m_vertices[t[1]], &c = m_vertices[t[2]];
  const double longest2 =
      std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
  if (longest2 == 0.0) return true;
  return (b - a).cross(c - a).norm() <= kDegenerateRelativeArea * longest2;
}

}  // namespace adb
