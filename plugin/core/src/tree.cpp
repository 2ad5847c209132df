// AdbTree construction: validates the settings, then runs the build stages in order.
#include "adb/core/tree.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "cell_count.h"
#include "format_number.h"
#include "node_occupancy.h"
#include "tree_builder.h"

namespace adb {
namespace {

using detail::formatNumber;

void validate(const BuildSettings& s) {
  if (s.gridResolution < 1 || s.gridResolution > 32) {
    throw SettingsError("BuildSettings::gridResolution is " + std::to_string(s.gridResolution) +
                        "; it must be in 1..32");
  }
  if (!(s.areaThreshold > 0.0 && s.areaThreshold <= 1.0)) {
    throw SettingsError("BuildSettings::areaThreshold is " + formatNumber(s.areaThreshold) +
                        "; it must be in (0, 1]");
  }
  if (s.maxLeafTriangles < 1 || s.maxLeafTriangles > 15) {
    throw SettingsError("BuildSettings::maxLeafTriangles is " +
                        std::to_string(s.maxLeafTriangles) + "; it must be in 1..15");
  }
}

// The tree stores boxes and areas in float, in local coordinates: a mesh must fit well inside
// float's range, with areas of its smallest triangles still normal floats.
constexpr double kMinMeshExtent = 1e-12;
constexpr double kMaxMeshExtent = 1e12;

// Rejects a mesh whose used vertices reach beyond detail::kMaxCoordinate (format_number.h says
// why), naming the first one.
void validateCoordinates(const TriangleMesh& mesh) {
  const Aabb& b = mesh.bounds();  // over the vertices that triangles use
  if (std::max(b.lo.cwiseAbs().maxCoeff(), b.hi.cwiseAbs().maxCoeff()) <= detail::kMaxCoordinate) {
    return;
  }
  for (const Triangle& t : mesh.triangles()) {
    for (std::uint32_t i : t) {
      const Vec3& v = mesh.vertices()[i];
      if (v.cwiseAbs().maxCoeff() <= detail::kMaxCoordinate) continue;
      throw MeshError(mesh.name() + ": vertex " + std::to_string(i) + " is at (" +
                      formatNumber(v.x()) + ", " + formatNumber(v.y()) + ", " +
                      formatNumber(v.z()) + "); an AdbTree supports coordinates up to " +
                      formatNumber(detail::kMaxCoordinate) +
                      " in magnitude (move the mesh nearer the origin)");
    }
  }
}

void validateExtent(const TriangleMesh& mesh) {
  // Finite: validateCoordinates bounds both ends by detail::kMaxCoordinate.
  const double extent = mesh.bounds().extent().maxCoeff();
  // Every vertex at one point: all triangles degenerate, handled by every stage (the local
  // frame puts the point at 0, so no float conversion is at stake).
  if (extent == 0.0) return;
  if (extent < kMinMeshExtent || extent > kMaxMeshExtent) {
    throw MeshError(mesh.name() + ": the mesh is " + formatNumber(extent) +
                    " units across; an AdbTree supports 1e-12 to 1e12 (rescale the mesh)");
  }
}

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

AdbTree::AdbTree(const TriangleMesh& mesh, const BuildSettings& settings) : m_settings(settings) {
  validate(settings);
  validateCoordinates(mesh);  // first: it makes the extent and the centre finite
  validateExtent(mesh);
  auto t0 = std::chrono::steady_clock::now();
  detail::buildHierarchy(*this, mesh, settings.maxLeafTriangles);
  detail::computeSurfaces(*this);
  detail::computeSlabs(*this);
  detail::computeOccupancy(*this);
  m_hierarchySeconds = secondsSince(t0);
  t0 = std::chrono::steady_clock::now();
  if (settings.counting == CellCounting::Exact) {
    detail::countCellsExact(*this);
  } else {
    detail::countCellsApproximate(*this);
  }
  m_countingSeconds = secondsSince(t0);
}

std::size_t AdbTree::memoryBytes() const {
  return m_nodes.capacity() * sizeof(Node) + m_surfaces.capacity() * sizeof(NodeSurface) +
         m_distributions.capacity() * sizeof(NodeDistribution) +
         m_occupancy.capacity() * sizeof(NodeOccupancy) +
         m_vertices.capacity() * sizeof(Vec3) + m_triangles.capacity() * sizeof(Triangle) +
         m_meshTriangle.capacity() * sizeof(std::uint32_t);
}

}  // namespace adb
