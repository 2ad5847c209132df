// Internal: how a node's box is partitioned into cells, for counting possible collision cells
// (paper §3.4) and for the pair probability (§3.5).
//
// [open] Cell shape. The paper partitions every box into a fixed G x G x G grid of cuboids.
// Tree nodes over a surface are thin slabs, and a G^3 grid on a slab has cells as thin as the
// slab is flat: a smooth surface crossing such a grid runs through several layers per column,
// no cell holds enough area, and pc is ~0 on every smooth mesh (measured in
// docs/probability-model.md). We keep about G^3 cells per node but make them as close to cubes
// as the box allows: g_i = round(e_i / h) cells along axis i, with the side h chosen so that
// prod max(1, e_i / h) = G^3. A slab gets one layer of near-cubic cells, a flat node one layer
// of flat cells (MaxArea -> the cell's face, so a fully covered flat cell counts), a cube the
// paper's G^3 cubes.
#pragma once

#include <algorithm>
#include <cmath>

#include "adb/core/tree.h"

namespace adb::detail {

/// Extents below this (absolute, local units) count as zero: a node that is a single point.
inline constexpr double kTinyExtent = 1e-30;
/// Area >= threshold is tested with this relative slack: a flat cell exactly covered by a
/// patch reaches MaxArea only up to rounding.
inline constexpr double kAreaTolerance = 1e-6;

inline Vec3 nodeExtent(const Node& n) { return n.boxHi() - n.boxLo(); }

/// A node's grid: cells per axis and the nominal cube side h.
struct GridShape {
  int cells[3] = {1, 1, 1};
  double side = kTinyExtent;
  int count() const { return cells[0] * cells[1] * cells[2]; }
};

/// About G^3 near-cubic cells over a box of the given extent (see the file comment).
inline GridShape gridShape(const Vec3& extent, int g) {
  const double target = static_cast<double>(g) * g * g;
  const Vec3 e = extent.cwiseMax(Vec3::Zero());
  int order[3] = {0, 1, 2};  // axes by decreasing extent
  std::sort(order, order + 3, [&](int a, int b) { return e[a] > e[b]; });
  const double e0 = e[order[0]], e1 = e[order[1]], e2 = e[order[2]];
  // Solve prod max(1, e_i / h) = target, dropping axes thinner than one cell.
  double h = std::cbrt(e0 * e1 * e2 / target);
  // (h > 0 guards the flat cases, where the product is 0 and every extent is ">= 0".)
  if (!(h > 0.0 && e2 >= h)) h = std::sqrt(e0 * e1 / target);
  if (!(h > 0.0 && e1 >= h)) h = e0 / target;
  GridShape shape;
  shape.side = std::max(h, kTinyExtent);
  for (int k = 0; k < 3; ++k) {
    const double n = std::round(e[k] / shape.side);
    shape.cells[k] = static_cast<int>(std::clamp(n, 1.0, target));
  }
  return shape;
}

}  // namespace adb::detail
