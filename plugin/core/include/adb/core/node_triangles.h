// The triangles below a node of an ADB-tree: one place for the fact that a subtree's leaves own
// a contiguous range of the tree-order triangles (AdbTree::triangles()). Brute-force oracles
// (adb-calibrate's labels, Bullet's contact audit) test the triangles of one node pair.
#pragma once

#include <cstdint>
#include <utility>

#include "adb/core/tree.h"

namespace adb {

/// [first, end) of the tree-order triangles below `node`: from its leftmost leaf's first to
/// its rightmost leaf's last.
inline std::pair<std::uint32_t, std::uint32_t> trianglesBelow(const AdbTree& tree,
                                                              std::uint32_t node) {
  const auto& nodes = tree.nodes();
  std::uint32_t left = node, right = node;
  while (!nodes[left].isLeaf()) left = nodes[left].firstChild();
  while (!nodes[right].isLeaf()) right = nodes[right].firstChild() + 1;
  return {nodes[left].firstTriangle(),
          nodes[right].firstTriangle() + nodes[right].triangleCount()};
}

}  // namespace adb
