// The paper's Fig. 8: how possible collision cells are distributed over the 512 cell indices
// of an 8 x 8 x 8 grid laid over each node's box, summed over a model's ADB-tree nodes.
//
// Our tree itself counts cells on a near-cubic grid per node (about G^3 cells shaped to the
// box, plugin/core/src/node_geometry.h); this histogram deliberately uses the paper's fixed
// 8^3 grid, so that it is comparable with the paper's figure. The possible-collision-cell
// rule is the tree's own (plugin/core/src/cell_count.cpp): a cell counts when the clipped
// triangle area in it reaches BuildSettings::areaThreshold x MaxArea(cell).
#pragma once

#include <cstdint>
#include <fstream>
#include <string>

#include "adb/core/tree.h"
#include "results.h"

namespace adb::tradeoff {

/// Clipping work allowed per model, in triangle-node incidences (each tree level holds every
/// triangle once, so a full count costs triangles x levels). Meshes up to ~100k triangles
/// are counted completely (~1 s). Above the budget, every s-th node of each level is
/// counted and its cells weighted by (nodes in the level / nodes counted in it): an unbiased
/// estimate of the full histogram at a bounded cost (~2-4 s for 1M triangles), so that it
/// never dominates the run. The stride is written to summary.md.
inline constexpr std::uint64_t kMaxHistogramWork = 2500000;

CellHistogram cellHistogram(const AdbTree& tree, std::uint64_t maxWork = kMaxHistogramWork);

/// cells.csv: `model,triangles,cell,count`, 512 rows per model.
extern const char* const kCellsCsvHeader;
void writeCellRows(std::ostream& out, const std::string& model, std::size_t triangles,
                   const CellHistogram& histogram);

}  // namespace adb::tradeoff
