// The paper's Fig. 8 over a built tree: how possible collision cells are distributed over the
// 512 cell indices of an 8 x 8 x 8 grid laid over each node's box, summed over the nodes.
//
// The tree counts cells on its own near-cubic grid per node (shaped to the box); this
// histogram uses the paper's fixed 8^3 grid, so that it compares with the paper's figure. The
// rule for a possible collision cell is the tree's own: the clipped triangle area in the cell
// reaches BuildSettings::areaThreshold x MaxArea(cell).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "adb/core/tree.h"

namespace adb {

/// Per cell index (x + 8y + 64z), the number of nodes for which that cell is a possible
/// collision cell.
struct CellHistogram {
  std::array<std::uint64_t, 512> count{};
  std::size_t nodesCounted = 0;
  std::size_t nodesTotal = 0;
  std::size_t stride = 1;  ///< 1: every node; s > 1: every s-th node per level, counts scaled
  double seconds = 0.0;    ///< wall clock of the count
};

/// Clipping work allowed by default, in triangle-node incidences (each tree level holds every
/// triangle once, so a full count costs triangles x levels): meshes up to ~100k triangles are
/// counted completely (~1 s).
inline constexpr std::uint64_t kMaxCellHistogramWork = 2500000;

/// Counts the histogram over `tree`. Above `maxWork`, every s-th node of each level is counted
/// and its cells weighted by (nodes in the level / nodes counted in it): an unbiased estimate
/// of the full histogram at a bounded cost (~2-4 s for 1M triangles).
CellHistogram cellHistogram(const AdbTree& tree, std::uint64_t maxWork = kMaxCellHistogramWork);

}  // namespace adb
