// Internal: counting possible collision cells pc(A) for every node (paper §3.4), exactly
// (clipping) or approximately (Fig. 5).
#pragma once

#include <vector>

#include "adb/core/tree.h"

namespace adb::detail {

/// Paper Fig. 5, for every node. Fills Node::pc.
void countCellsApproximate(AdbTree& tree);
/// Clips every triangle below a node into the node's grid, for every node. Fills Node::pc.
void countCellsExact(AdbTree& tree);

/// The approximate count of one node (exposed for tests).
double approximateCellCount(const AdbTree& tree, std::uint32_t node);
/// The exact count of one node; `cellArea` is scratch, resized as needed.
double exactCellCount(const AdbTree& tree, std::uint32_t node, std::uint32_t firstTriangle,
                      std::uint32_t lastTriangle, std::vector<double>& cellArea);

}  // namespace adb::detail
