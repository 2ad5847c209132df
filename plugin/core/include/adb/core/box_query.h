// Triangles of a tree that may overlap an axis-aligned box: the query a physics engine's
// concave-shape interface asks (Bullet's processAllTriangles), answered with the hierarchy.
#pragma once

#include <cstdint>

#include "adb/core/tree.h"

namespace adb {

/// Calls f(treeTriangle) for every triangle of `tree` in a leaf whose box overlaps
/// `meshBox` (mesh coordinates, touching included). `treeTriangle` indexes
/// tree.triangles(); tree.meshTriangle() maps it back to the mesh. Leaves are reported
/// whole: a caller wanting exact overlap tests the triangles itself. No allocation.
template <typename F>
void forEachTriangleNear(const AdbTree& tree, const Aabb& meshBox, F&& f) {
  if (meshBox.empty()) return;
  const Vec3 lo = meshBox.lo - tree.origin();
  const Vec3 hi = meshBox.hi - tree.origin();
  const auto& nodes = tree.nodes();
  // A balanced tree over at most 2^28 triangles is at most 29 levels deep: the stack holds
  // at most one pending sibling per level.
  std::uint32_t stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes[stack[--top]];
    if ((n.boxLo().array() > hi.array()).any() || (n.boxHi().array() < lo.array()).any()) {
      continue;
    }
    if (n.isLeaf()) {
      for (std::uint32_t t = n.firstTriangle(); t < n.firstTriangle() + n.triangleCount(); ++t) f(t);
    } else {
      stack[top++] = n.firstChild();
      stack[top++] = n.firstChild() + 1;
    }
  }
}

/// Calls f(treeTriangle) for every triangle of `tree` in a leaf whose box overlaps the
/// oriented box `meshBox` (mesh coordinates). A convex shape's own bounds turned into the
/// mesh frame stay tight where its axis-aligned box would not: a wall's box tilted against
/// a mesh covers the whole mesh as an AABB. Nodes are tested on the 6 face axes of the two
/// boxes (conservative: the 9 edge axes would prune a few more). No allocation.
template <typename F>
void forEachTriangleNear(const AdbTree& tree, const OrientedBox& meshBox, F&& f) {
  if (!(meshBox.half.array() >= 0.0).all() || !meshBox.centre.allFinite()) return;
  const Vec3 centre = meshBox.centre - tree.origin();
  const Mat3& axes = meshBox.axes;
  const Mat3 absAxes = axes.cwiseAbs();
  const Vec3 extent = absAxes * meshBox.half;  // its half extents along the tree's axes
  const auto& nodes = tree.nodes();
  std::uint32_t stack[64];  // one pending sibling per level, as above
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes[stack[--top]];
    const Vec3 half = 0.5 * (n.boxHi() - n.boxLo());
    const Vec3 offset = centre - 0.5 * (n.boxHi() + n.boxLo());
    if ((offset.cwiseAbs().array() > (half + extent).array()).any()) continue;
    const Vec3 along = axes.transpose() * offset;  // on the oriented box's axes
    if ((along.cwiseAbs().array() > (meshBox.half + absAxes.transpose() * half).array()).any()) {
      continue;
    }
    if (n.isLeaf()) {
      for (std::uint32_t t = n.firstTriangle(); t < n.firstTriangle() + n.triangleCount(); ++t) f(t);
    } else {
      stack[top++] = n.firstChild();
      stack[top++] = n.firstChild() + 1;
    }
  }
}

}  // namespace adb
