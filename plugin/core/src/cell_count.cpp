// Possible-collision-cell counts pc(A) (paper §3.4): the exact clipping count and the
// approximate Fig. 5 propagation, over each node's near-cubic grid (node_geometry.h).
//
// Fig. 5, as implemented (h is the side of A's near-cubic cells):
//
//   posColCells(A, A'):
//     if A' fits in one cell (e_max(A') <= h) or A' is a leaf:
//       return min(k, Area(A') / h^2)     # k = cells A's box spans (at least 1 per axis)
//     return sum over children A'[i] of posColCells(A, A'[i])
//
// [open] The paper's small-node case counts 1 when Area(A') >= MaxArea(c_A), and its leaf case
// k^(2/3) when the leaf holds enough area (the rule itself is in the unavailable extended
// version). In a balanced tree the first node no bigger than a cell straddles 2-4 cells and
// holds 0.3-1 h^2 of surface, so the 0/1 rule counts almost none of them (measured: pc ~2 at
// depth 3 where the exact count is ~80). We count instead the cells the surface crosses,
// S / h^2 (the paper's k^(2/3) is the same number for a cube-shaped leaf), never more than
// the cells the node's box spans. With the threshold at 0.35 MaxArea (area >= h^2 / 2 for a
// cube), the exact count of crossed cells holding that much matches it within the tolerance
// stated in tests/core/test_cell_count.cpp.
#include "cell_count.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "cell_grid.h"
#include "node_geometry.h"
#include "tree_builder.h"

namespace adb::detail {
namespace {

// The cell size of a node's grid, per axis (zero for a flat axis: a flat cell).
Vec3 cellSize(const Node& n, const GridShape& shape) {
  const Vec3 e = nodeExtent(n);
  return Vec3(e.x() / shape.cells[0], e.y() / shape.cells[1], e.z() / shape.cells[2]);
}

// The area a cell must hold to be a possible collision cell: the configured fraction of
// MaxArea, lowered by the rounding tolerance.
double cellThreshold(const AdbTree& tree, const Node& n, const GridShape& shape) {
  return maxPolygonArea(cellSize(n, shape)) * tree.settings().areaThreshold *
         (1.0 - kAreaTolerance);
}

bool enoughArea(double area, double threshold) { return area > 0.0 && area >= threshold; }

GridShape shapeOf(const AdbTree& tree, const Node& n) {
  return gridShape(nodeExtent(n), tree.settings().gridResolution);
}

}  // namespace

double approximateCellCount(const AdbTree& tree, std::uint32_t node) {
  const auto& nodes = tree.nodes();
  const auto& surf = tree.surfaces();
  const GridShape shape = shapeOf(tree, nodes[node]);
  const double h = shape.side;
  double pc = 0.0;
  // Explicit stack: the walk grows by one entry per level, and a balanced tree over at most
  // 2^28 triangles is at most 29 levels deep.
  std::uint32_t stack[64];
  int top = 0;
  stack[top++] = node;
  while (top > 0) {
    const std::uint32_t i = stack[--top];
    const Node& n = nodes[i];
    const Vec3 e = nodeExtent(n);
    if (e.maxCoeff() <= h || n.isLeaf()) {
      const double spanned = e.cwiseMax(Vec3::Constant(h)).prod() / (h * h * h);
      pc += std::min(spanned, surf[i].area / (h * h));
    } else {
      stack[top++] = n.firstChild();
      stack[top++] = n.firstChild() + 1;
    }
  }
  return std::min(pc, static_cast<double>(shape.count()));
}

double exactCellCount(const AdbTree& tree, std::uint32_t node, std::uint32_t firstTriangle,
                      std::uint32_t lastTriangle, std::vector<double>& cellArea) {
  const Node& n = tree.nodes()[node];
  const GridShape shape = shapeOf(tree, n);
  const CellGrid grid = CellGrid::over(Aabb{n.boxLo(), n.boxHi()}, shape.cells, 0.0);
  cellArea.assign(static_cast<std::size_t>(shape.count()), 0.0);
  const auto& verts = tree.localVertices();
  const auto& tris = tree.triangles();
  for (std::uint32_t t = firstTriangle; t < lastTriangle; ++t) {
    accumulateClippedArea(grid, verts[tris[t][0]], verts[tris[t][1]], verts[tris[t][2]],
                          cellArea.data());
  }
  const double threshold = cellThreshold(tree, n, shape);
  double pc = 0.0;
  for (double a : cellArea) pc += enoughArea(a, threshold) ? 1.0 : 0.0;
  return pc;
}

void fillCellStatistics(AdbTree& tree) {
  auto& cells = TreeBuilderAccess::distributions(tree);
  const auto& nodes = tree.nodes();
  cells.resize(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const GridShape shape = shapeOf(tree, nodes[i]);
    cells[i].side = static_cast<float>(shape.side);
    cells[i].invSide = 1.0f / cells[i].side;  // side >= kTinyExtent: finite in float
    cells[i].density =
        static_cast<float>(std::clamp(nodes[i].pc / static_cast<double>(shape.count()), 0.0, 1.0));
  }
}

void countCellsApproximate(AdbTree& tree) {
  auto& nodes = TreeBuilderAccess::nodes(tree);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    nodes[i].pc = static_cast<float>(approximateCellCount(tree, static_cast<std::uint32_t>(i)));
  }
  fillCellStatistics(tree);
}

void countCellsExact(AdbTree& tree) {
  auto& nodes = TreeBuilderAccess::nodes(tree);
  const auto ranges = triangleRanges(tree);
  std::vector<double> cellArea;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const auto [first, last] = ranges[i];
    nodes[i].pc = static_cast<float>(
        exactCellCount(tree, static_cast<std::uint32_t>(i), first, last, cellArea));
  }
  fillCellStatistics(tree);
}

}  // namespace adb::detail
