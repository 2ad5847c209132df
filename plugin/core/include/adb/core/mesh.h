// TriangleMesh: an indexed triangle mesh, validated once at construction.
//
// Validation follows "validate once, at the door": a mesh that exists is valid, so the tree
// builder and queries never re-check. Bad input (NaN/infinite coordinates, out-of-range
// indices, no triangles) throws adb::MeshError naming the offending vertex or triangle.
// Degenerate triangles (zero area, repeated vertices, collinear) are legal: they are kept,
// counted and reported, and every later stage handles them.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "adb/core/errors.h"
#include "adb/core/geometry.h"

namespace adb {

using Triangle = std::array<std::uint32_t, 3>;

/// Counts of what validation found that is legal but worth knowing.
struct MeshReport {
  std::size_t degenerateTriangles = 0;  ///< zero area: repeated vertices or collinear
  std::size_t repeatedVertexTriangles = 0;  ///< of those, with two equal indices/positions
  std::size_t unusedVertices = 0;
};

class TriangleMesh {
 public:
  /// Validates and stores the mesh. `name` is used in error messages (a file name, say).
  /// Throws MeshError on NaN/infinite coordinates, out-of-range indices or no triangles.
  TriangleMesh(std::vector<Vec3> vertices, std::vector<Triangle> triangles,
               std::string name = "mesh");

  const std::vector<Vec3>& vertices() const { return m_vertices; }
  const std::vector<Triangle>& triangles() const { return m_triangles; }
  std::size_t triangleCount() const { return m_triangles.size(); }
  const std::string& name() const { return m_name; }
  const MeshReport& report() const { return m_report; }
  /// Bounding box of the vertices that triangles use, in the mesh's own coordinates.
  const Aabb& bounds() const { return m_bounds; }

  /// Area of triangle i (0 for degenerate ones).
  double triangleArea(std::size_t i) const;
  /// True when triangle i has zero area (within a relative tolerance of its edge lengths).
  bool isDegenerate(std::size_t i) const;

 private:
  std::vector<Vec3> m_vertices;
  std::vector<Triangle> m_triangles;
  std::string m_name;
  MeshReport m_report;
  Aabb m_bounds;
};

}  // namespace adb
