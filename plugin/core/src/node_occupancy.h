// Internal: which cells of a node's box its triangles touch — the conservative counterpart of
// the possible collision cells (cell_count.h).
//
// The cell model prunes a pair whose rounded density leaves one side no possible collision
// cell. That is an estimate: on meshes of slivers and large flat triangles a node's triangles
// cover too little of any cell to count, and pairs whose triangles do intersect were dropped
// as empty (issue 37: 22 % of a low-poly robot's colliding poses answered "no", most with
// confidence >= 0.99). The occupancy is a proof instead: bit c is set when some triangle below
// the node touches cell c (a separating-axis test against the cell grown by a small margin),
// so where the part of a node's box that the other node's box can reach holds no set bit, no
// triangle of the node can meet the other's, and the pair is certainly apart. It is also a
// tighter bounding volume than the box for a long diagonal sliver, which fills few of its
// box's cells.
//
// The 64 cells are 2^shift[k] slices along axis k with shifts summing to 6, each doubling given
// to the axis whose slices are widest, so that cells are near cubic (a flat node gets 8 x 8 x 1).
// Bit index: x + (y << shift[0]) + (z << (shift[0] + shift[1])).
#pragma once

#include <cstdint>

#include "adb/core/tree.h"

namespace adb::detail {

/// Margins, in slices and relative to the node's size: the build and a query map a coordinate
/// to a slice with the same formula and the same stored scale, but the build tests a triangle
/// against a cell's bounds, which round differently. The build grows each cell by more than a
/// query grows its box, so a point in a queried box always lands in a cell that was tested
/// with room to spare.
inline constexpr double kQuerySliceMargin = 1e-4;
inline constexpr double kBuildSliceMargin = 2e-4;
inline constexpr double kBuildRelativeMargin = 1e-6;

/// The layout of a box of the given extent (see the file comment): shifts, and the slices per
/// unit length along each axis (0 along a flat axis, which is never split).
NodeOccupancy occupancyLayout(const Vec3& extent);

/// The slice of coordinate offset t = (x - lo) * scale among n slices, clamped to the grid (a
/// box beyond it is the box test's business); `ifNaN` for an undefined offset.
inline int occupancySlice(double t, int n, int ifNaN) {
  if (t >= static_cast<double>(n)) return n - 1;
  if (t >= 0.0) return static_cast<int>(t);
  return t < 0.0 ? 0 : ifNaN;
}

/// The cells of slices from[k]..to[k] (inclusive) along each axis.
inline std::uint64_t occupancyCells(const NodeOccupancy& o, const int from[3], const int to[3]) {
  // Bits [lo, hi) of a word, 0 <= lo < hi <= 64.
  const auto bits = [](int lo, int hi) {
    return (hi >= 64 ? ~0ull : (1ull << hi) - 1) & ~((1ull << lo) - 1);
  };
  // A 1 at every multiple of 2^s: a pattern of 2^s bits repeated over the word.
  static constexpr std::uint64_t kRepeat[7] = {~0ull,
                                               0x5555555555555555ull,
                                               0x1111111111111111ull,
                                               0x0101010101010101ull,
                                               0x0001000100010001ull,
                                               0x0000000100000001ull,
                                               1ull};
  const int sx = o.shift[0], sxy = o.shift[0] + o.shift[1];
  const std::uint64_t x = bits(from[0], to[0] + 1) * kRepeat[sx];
  const std::uint64_t y = bits(from[1] << sx, (to[1] + 1) << sx) * kRepeat[sxy];
  const std::uint64_t z = bits(from[2] << sxy, (to[2] + 1) << sxy);
  return x & y & z;
}

/// The slices of node n's grid that the box [lo, hi] of its local frame spans along each axis,
/// from[k]..to[k] inclusive; false for an empty box (lo > hi on an axis).
inline bool occupancySpan(const Node& n, const NodeOccupancy& o, const Vec3& lo, const Vec3& hi,
                          int from[3], int to[3]) {
  for (int k = 0; k < 3; ++k) {
    if (lo[k] > hi[k]) return false;
    const int slices = 1 << o.shift[k];
    const double scale = o.scale[k];
    from[k] = occupancySlice((lo[k] - n.lo[k]) * scale - kQuerySliceMargin, slices, 0);
    to[k] = occupancySlice((hi[k] - n.lo[k]) * scale + kQuerySliceMargin, slices, slices - 1);
  }
  return true;
}

/// Whether node n (occupancy o) has a triangle that may reach into the box [lo, hi] of its
/// local frame: false proves that none does. An empty box (lo > hi on an axis) holds none.
inline bool occupiedWithin(const Node& n, const NodeOccupancy& o, const Vec3& lo, const Vec3& hi) {
  int from[3], to[3];
  return occupancySpan(n, o, lo, hi, from, to) && (o.cells & occupancyCells(o, from, to)) != 0;
}

/// How full of node n's triangles the part of its box within [lo, hi] is: the share of the
/// cells it spans that some triangle touches, in [0, 1]; 0 for an empty box. A large flat
/// triangle fills every cell it crosses, where the cell model's area threshold may count none
/// (issue 43: the evidence of pairs the model is blind to).
inline double occupiedFill(const Node& n, const NodeOccupancy& o, const Vec3& lo,
                           const Vec3& hi) {
  int from[3], to[3];
  if (!occupancySpan(n, o, lo, hi, from, to)) return 0.0;
  const int spanned = (to[0] - from[0] + 1) * (to[1] - from[1] + 1) * (to[2] - from[2] + 1);
  const int occupied = __builtin_popcountll(o.cells & occupancyCells(o, from, to));
  return spanned > 0 ? static_cast<double>(occupied) / spanned : 0.0;
}

/// Fills the tree's occupancy, one record per node (needs the hierarchy).
void computeOccupancy(AdbTree& tree);

}  // namespace adb::detail
