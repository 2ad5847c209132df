// Internal (not public API): the regular G x G x G cell grid of one tree node, the exact
// per-cell clipped triangle area of the ADB-tree "exact" algorithm, and MaxArea(cell), the
// largest planar polygon that fits in a cell. The tree builder sums clipped areas per cell
// and counts the cells whose sum reaches maxPolygonArea(cellSize).
#pragma once

#include "adb/core/geometry.h"

namespace adb::detail {

/// Resolutions outside [kMinGridResolution, kMaxGridResolution] are clamped by CellGrid::over.
inline constexpr int kMinGridResolution = 1;
inline constexpr int kMaxGridResolution = 32;

/// Absolute floor (in model units) on every padded box extent, so that a box that is a single
/// point still has cellSize > 0. Far from the origin the floor is raised to
/// kMinExtentUlps * eps * (largest |coordinate| of the box), so that the grid planes stay
/// distinct doubles there (see CellGrid::over).
inline constexpr double kMinGridExtent = 1e-30;
inline constexpr double kMinExtentUlps = 1024.0;

/// Cells per axis at most (a needle-shaped node gets up to G^3 cells along its length).
inline constexpr int kMaxCellsPerAxis = 32 * 32 * 32;

/// A node's cell grid: box lo corner, per-axis cell size and cell count.
/// Cells are indexed (iz * cells[1] + iy) * cells[0] + ix.
struct CellGrid {
  Vec3 lo;
  Vec3 cellSize;  // per axis, > 0 (the caller pads zero extents, see over())
  int cells[3];   // per axis

  /// The grid over `box` with `resolution` cells on every axis (clamped to 1..32).
  /// Degenerate boxes are padded, keeping lo and moving hi up: every extent is raised to at
  /// least minRelativeThickness (clamped to [0, 1]; NaN counts as 0) times the largest
  /// extent, and to at least max(kMinGridExtent, kMinExtentUlps * eps * max |coordinate|).
  /// A flat patch thus sits in the lowest cell layer of its thin axis. An empty or
  /// non-finite box gives a grid of floor-sized cells at the origin (callers never ask).
  static CellGrid over(const Aabb& box, int resolution, double minRelativeThickness);
  /// The same with its own cell count per axis (each clamped to 1..kMaxCellsPerAxis).
  static CellGrid over(const Aabb& box, const int (&cellsPerAxis)[3],
                       double minRelativeThickness);

  int cellCount() const { return cells[0] * cells[1] * cells[2]; }
  int cellIndex(int ix, int iy, int iz) const { return (iz * cells[1] + iy) * cells[0] + ix; }
};

/// Adds the area of triangle (a, b, c) clipped into each cell to cellArea[cellIndex]
/// (cellArea has cellCount() entries). Pieces outside the grid are clamped into the border cells
/// (the triangle is expected to lie inside the box up to rounding).
///
/// `grid` must come from CellGrid::over (1 <= G <= 32, cellSize > 0).
/// Area is conserved: the added areas sum to the triangle's area up to rounding (the rounding
/// residual of the clipping, large only for slivers, is given to the cell of the largest
/// piece). A piece with zero extent along an axis (a triangle lying in a grid plane, say)
/// goes to the single slab floor((coord - lo) / cellSize), clamped to [0, G-1], so it is
/// counted once. Zero-area triangles add nothing. The net amount added to each cell is finite
/// and >= 0; a triangle whose area overflows (coordinates near 1e154 and beyond) adds nothing.
void accumulateClippedArea(const CellGrid& grid, const Vec3& a, const Vec3& b, const Vec3& c,
                           double* cellArea);

/// Largest planar polygon area fitting in a cuboid cell with sides p <= q <= r:
/// r * sqrt(p^2 + q^2) (the diagonal rectangle; a^2 sqrt 2 for a cube, q*r for a flat cell).
/// Signs of the components are ignored.
double maxPolygonArea(const Vec3& cellSize);

}  // namespace adb::detail
