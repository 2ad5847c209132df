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

double secondsSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

AdbTree::AdbTree(const TriangleMesh& mesh, const BuildSettings& settings) : m_settings(settings) {
  validate(settings);
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
