// Triangles of a tree that may overlap a box, axis-aligned (the query a physics engine's
// concave-shape interface asks: Bullet's processAllTriangles) or oriented (a convex shape's
// own bounds), answered with the hierarchy.
#pragma once

#include <cstddef>
#include <cstdint>

#include "adb/core/tree.h"

namespace adb {

namespace detail {

/// The walk both queries share: calls f(treeTriangle) for every triangle in a leaf whose
/// box (tree-local) passes `overlaps`, descending only into nodes that pass it. Returns the
/// nodes visited. A balanced tree over at most 2^28 triangles is at most 29 levels deep:
/// the stack holds at most one pending sibling per level.
template <typename Overlaps, typename F>
std::size_t forEachTriangleWhere(const AdbTree& tree, Overlaps&& overlaps, F&& f) {
  const auto& nodes = tree.nodes();
  std::uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  std::size_t visited = 0;
  while (top > 0) {
    const Node& n = nodes[stack[--top]];
    ++visited;
    if (!overlaps(n)) continue;
    if (n.isLeaf()) {
      for (std::uint32_t t = n.firstTriangle(); t < n.firstTriangle() + n.triangleCount(); ++t) f(t);
    } else {
      stack[top++] = n.firstChild();
      stack[top++] = n.firstChild() + 1;
    }
  }
  return visited;
}

}  // namespace detail

/// Calls f(treeTriangle) for every triangle of `tree` in a leaf whose box overlaps
/// `meshBox` (mesh coordinates, touching included). `treeTriangle` indexes
/// tree.triangles(); tree.meshTriangle() maps it back to the mesh. Leaves are reported
/// whole: a caller wanting exact overlap tests the triangles itself. No allocation. Returns
/// the nodes visited (the query's work).
template <typename F>
std::size_t forEachTriangleNear(const AdbTree& tree, const Aabb& meshBox, F&& f) {
  if (meshBox.empty()) return 0;
  const Vec3 lo = meshBox.lo - tree.origin();
  const Vec3 hi = meshBox.hi - tree.origin();
  return detail::forEachTriangleWhere(
      tree,
      [&](const Node& n) {
        return !((n.boxLo().array() > hi.array()).any() || (n.boxHi().array() < lo.array()).any());
      },
      f);
}

/// Calls f(treeTriangle) for every triangle of `tree` in a leaf whose box overlaps the
/// oriented box `meshBox` (mesh coordinates). A convex shape's own bounds turned into the
/// mesh frame stay tight where its axis-aligned box would not: a wall's box tilted against
/// a mesh covers the whole mesh as an AABB. Nodes are tested on the 6 face axes of the two
/// boxes (conservative: the 9 edge axes would prune a few more). No allocation. Returns the
/// nodes visited.
template <typename F>
std::size_t forEachTriangleNear(const AdbTree& tree, const OrientedBox& meshBox, F&& f) {
  if (!(meshBox.half.array() >= 0.0).all() || !meshBox.half.allFinite() ||
      !meshBox.centre.allFinite()) {
    return 0;
  }
  const Vec3 centre = meshBox.centre - tree.origin();
  const Mat3& axes = meshBox.axes;
  const Mat3 absAxes = axes.cwiseAbs();
  const Vec3 extent = absAxes * meshBox.half;  // its half extents along the tree's axes
  return detail::forEachTriangleWhere(
      tree,
      [&](const Node& n) {
        const Vec3 half = 0.5 * (n.boxHi() - n.boxLo());
        const Vec3 offset = centre - 0.5 * (n.boxHi() + n.boxLo());
        if ((offset.cwiseAbs().array() > (half + extent).array()).any()) return false;
        const Vec3 along = axes.transpose() * offset;  // on the oriented box's axes
        return !(along.cwiseAbs().array() > (meshBox.half + absAxes.transpose() * half).array())
                    .any();
      },
      f);
}

}  // namespace adb
