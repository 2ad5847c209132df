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

}  // namespace adb
