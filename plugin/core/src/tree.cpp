// AdbTree construction: validates the settings, then runs the build stages in order.
#include "adb/core/tree.h"

#include <chrono>
#include <string>

#include "cell_count.h"
#include "tree_builder.h"

namespace adb {
namespace {

void validate(const BuildSettings& s) {
  if (s.gridResolution < 1 || s.gridResolution > 32) {
    throw SettingsError("BuildSettings::gridResolution is " + std::to_string(s.gridResolution) +
                        "; it must be in 1..32");
  }
  if (!(s.areaThreshold > 0.0 && s.areaThreshold <= 1.0)) {
    throw SettingsError("BuildSettings::areaThreshold is " + std::to_string(s.areaThreshold) +
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

void validateExtent(const TriangleMesh& mesh) {
  const double extent = mesh.bounds().extent().maxCoeff();
  if (extent == 0.0) return;  // every vertex at one point: all degenerate, handled
  if (extent < kMinMeshExtent || extent > kMaxMeshExtent) {
    throw MeshError(mesh.name() + ": the mesh is " + std::to_string(extent) +
                    " units across; an AdbTree supports 1e-12 to 1e12 (rescale the mesh)");
  }
}

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

AdbTree::AdbTree(const TriangleMesh& mesh, const BuildSettings& settings) : m_settings(settings) {
  validate(settings);
  validateExtent(mesh);
  auto t0 = std::chrono::steady_clock::now();
  detail::buildHierarchy(*this, mesh, settings.maxLeafTriangles);
  detail::computeSurfaces(*this);
  detail::computeSlabs(*this);
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
         m_vertices.capacity() * sizeof(Vec3) + m_triangles.capacity() * sizeof(Triangle) +
         m_meshTriangle.capacity() * sizeof(std::uint32_t);
}

}  // namespace adb
