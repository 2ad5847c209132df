// The paper's Fig. 8 histogram over a built tree, with the tree's own grid and clipping.
#include "adb/core/cell_histogram.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include "cell_grid.h"
#include "node_geometry.h"
#include "tree_builder.h"

namespace adb {

namespace {

constexpr int kGrid = 8;  // the paper's 8^3 = 512 cells
constexpr std::size_t kCells = kGrid * kGrid * kGrid;

// Node indices by level, root first.
std::vector<std::vector<std::uint32_t>> levels(const AdbTree& tree) {
  std::vector<std::vector<std::uint32_t>> out{{0}};
  while (true) {
    std::vector<std::uint32_t> next;
    for (std::uint32_t i : out.back()) {
      const Node& n = tree.nodes()[i];
      if (n.isLeaf()) continue;
      next.push_back(n.firstChild());
      next.push_back(n.firstChild() + 1);
    }
    if (next.empty()) return out;
    out.push_back(std::move(next));
  }
}

// Adds `weight` to every possible collision cell of the node on the fixed 8^3 grid.
void countNode(const AdbTree& tree, std::uint32_t node, std::uint32_t first, std::uint32_t last,
               double weight, std::vector<double>& cellArea, std::array<double, kCells>& count) {
  const Node& n = tree.nodes()[node];
  const detail::CellGrid grid = detail::CellGrid::over(Aabb{n.boxLo(), n.boxHi()}, kGrid, 0.0);
  cellArea.assign(kCells, 0.0);
  const auto& v = tree.localVertices();
  const auto& tris = tree.triangles();
  for (std::uint32_t t = first; t < last; ++t) {
    detail::accumulateClippedArea(grid, v[tris[t][0]], v[tris[t][1]], v[tris[t][2]],
                                  cellArea.data());
  }
  // The same threshold as cell_count.cpp: a fraction of MaxArea, less the rounding slack.
  const double threshold = detail::maxPolygonArea(grid.cellSize) *
                           tree.settings().areaThreshold * (1.0 - detail::kAreaTolerance);
  // CellGrid's index (iz * 8 + iy) * 8 + ix is the paper's x + 8y + 64z.
  for (std::size_t c = 0; c < kCells; ++c) {
    if (cellArea[c] > 0.0 && cellArea[c] >= threshold) count[c] += weight;
  }
}

}  // namespace

CellHistogram cellHistogram(const AdbTree& tree, std::uint64_t maxWork) {
  const auto start = std::chrono::steady_clock::now();
  CellHistogram h;
  h.nodesTotal = tree.nodes().size();
  const auto ranges = detail::triangleRanges(tree);
  const auto byLevel = levels(tree);
  const std::uint64_t fullWork = static_cast<std::uint64_t>(tree.triangleCount()) * byLevel.size();
  h.stride = static_cast<std::size_t>((fullWork + maxWork - 1) / std::max<std::uint64_t>(maxWork, 1));
  h.stride = std::max<std::size_t>(h.stride, 1);
  std::array<double, kCells> weighted{};
  std::vector<double> cellArea;
  for (const std::vector<std::uint32_t>& level : byLevel) {
    const std::size_t sampled = (level.size() + h.stride - 1) / h.stride;
    const double weight = static_cast<double>(level.size()) / static_cast<double>(sampled);
    for (std::size_t k = 0; k < level.size(); k += h.stride) {
      const std::uint32_t i = level[k];
      countNode(tree, i, ranges[i].first, ranges[i].second, weight, cellArea, weighted);
    }
    h.nodesCounted += sampled;
  }
  for (std::size_t c = 0; c < kCells; ++c) h.count[c] = static_cast<std::uint64_t>(std::llround(weighted[c]));
  h.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return h;
}

}  // namespace adb
