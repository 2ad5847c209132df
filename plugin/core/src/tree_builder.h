// Internal: the stages of AdbTree construction (hierarchy, surfaces, cell counts), each a
// free function over the tree's arrays so that it can be tested and timed alone.
#pragma once

#include <vector>

#include "adb/core/tree.h"

namespace adb {

/// Grants the build stages write access to AdbTree's arrays.
struct TreeBuilderAccess {
  static NodeArray<Node>& nodes(AdbTree& t) { return t.m_nodes; }
  static std::vector<NodeSurface>& surfaces(AdbTree& t) { return t.m_surfaces; }
  static NodeArray<NodeDistribution>& distributions(AdbTree& t) { return t.m_distributions; }
  static std::vector<NodeOccupancy>& occupancy(AdbTree& t) { return t.m_occupancy; }
  static std::vector<Vec3>& vertices(AdbTree& t) { return t.m_vertices; }
  static std::vector<Triangle>& triangles(AdbTree& t) { return t.m_triangles; }
  static std::vector<std::uint32_t>& meshTriangle(AdbTree& t) { return t.m_meshTriangle; }
  static Vec3& origin(AdbTree& t) { return t.m_origin; }
  static int& maxDepth(AdbTree& t) { return t.m_maxDepth; }
};

namespace detail {

/// Builds the AABB hierarchy: fills nodes (boxes, children, leaf ranges), the tree-ordered
/// triangles and their mesh indices, local vertices and the max depth. pc is left at 0.
void buildHierarchy(AdbTree& tree, const TriangleMesh& mesh, int maxLeafTriangles);

/// Fills the per-node surface statistics bottom-up.
void computeSurfaces(AdbTree& tree);

/// Fills the slab of every node's NodeDistribution (normal, offset, half width): needs the
/// surfaces. Resizes the distributions to the node count.
void computeSlabs(AdbTree& tree);

/// Per-node triangle ranges [first, last) in tree order (inner nodes own their subtree's).
std::vector<std::pair<std::uint32_t, std::uint32_t>> triangleRanges(const AdbTree& tree);

}  // namespace detail
}  // namespace adb
