// Triangles of a tree that may overlap a box, axis-aligned (the query a physics engine's
// concave-shape interface asks: Bullet's processAllTriangles) or oriented (a convex shape's
// own bounds), answered with the hierarchy.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>

#include "adb/core/detail/box_query_walk.h"
#include "adb/core/tree.h"

namespace adb {

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
  const detail::OrientedBoxOverlap overlaps(meshBox.centre - tree.origin(), meshBox.axes,
                                            meshBox.half);
  return detail::forEachTriangleWhere(tree, overlaps, f);
}

/// Calls f(treeTriangle) for triangles of `tree` within `reach` of the box `solid`
/// (tree-local: mesh coordinates minus tree.origin()), sampling the deepest contacts
/// instead of visiting every such triangle: the tree is cut into regions `regionLevel`
/// levels below the root, and inside a region a node or triangle is visited only if some
/// point of it could lie deeper inside `solid` than the region's deepest contact so far by
/// more than `slack`. f(t) returns the depth it found for tree triangle t (negative when
/// apart, -infinity for no contact).
/// Why: a body resting on a floor or wall box has hundreds of triangles within reach, all
/// nearly as deep; a manifold keeps 4 points, the deepest and the most spread. Each region
/// still gives a contact within `slack` of its deepest (branch and bound on the maximum),
/// so the contacts that hold the body are kept, at a fraction of the tests. A node's bound
/// is its box cut by its slab (a flat patch tilted in the mesh frame has boxes much deeper
/// than its triangles); a triangle's, its vertices'. Deeper-bounded children are entered
/// first, so that the region's best is found early. No allocation. Returns the nodes
/// visited (f's calls are counted by the caller).
template <typename F>
std::size_t forEachDeepestTriangleNear(const AdbTree& tree, const OrientedBox& solid,
                                       double reach, int regionLevel, double slack, F&& f) {
  if (!(solid.half.array() >= 0.0).all() || !solid.half.allFinite() ||
      !solid.centre.allFinite() || !solid.axes.allFinite() || !(reach >= 0.0) ||
      !std::isfinite(reach) || !(slack >= 0.0)) {
    return 0;
  }
  const auto& nodes = tree.nodes();
  const auto& slabs = tree.distributions();
  const auto& vertices = tree.localVertices();
  // The cheap test first: most nodes of a big mesh under a small box fail it.
  const detail::OrientedBoxOverlap overlaps(solid.centre, solid.axes,
                                            solid.half + Vec3::Constant(reach));
  const auto nodeBound = [&](std::uint32_t i) {
    return detail::deepestPossible(nodes[i], slabs[i], solid);
  };
  const auto triangleBound = [&](std::uint32_t t) {
    double deepest = std::numeric_limits<double>::infinity();
    const Triangle& tri = tree.triangles()[t];
    const Vec3 p0 = vertices[tri[0]] - solid.centre, p1 = vertices[tri[1]] - solid.centre,
               p2 = vertices[tri[2]] - solid.centre;
    for (int k = 0; k < 3; ++k) {
      const Vec3 axis = solid.axes.col(k);
      const double q0 = axis.dot(p0), q1 = axis.dot(p1), q2 = axis.dot(p2);
      const double nearest = std::max({0.0, std::min({q0, q1, q2}), -std::max({q0, q1, q2})});
      deepest = std::min(deepest, solid.half[k] - nearest);
    }
    return deepest;
  };
  // A region starts with nothing found: only what comes within reach counts (a point
  // farther than `reach` outside the box has a bound below -reach).
  const double none = -reach - slack;
  // Regions are subtrees and the walk is depth first: one region is open at a time, and
  // its entries are all popped before the next region's root.
  struct Entry {
    std::uint32_t node;
    int level;     // below the root; -1 inside a region
    double bound;  // inside a region: nodeBound, computed when its parent ordered it
  };
  Entry stack[64];
  int top = 0;
  stack[top++] = Entry{0, 0, 0.0};
  double best = none;  // the open region's deepest contact
  std::size_t visited = 0;
  while (top > 0) {
    const Entry e = stack[--top];
    const Node& n = nodes[e.node];
    ++visited;
    const bool regionRoot = e.level >= regionLevel || (e.level >= 0 && n.isLeaf());
    if (regionRoot) best = none;
    const bool inRegion = e.level < 0 || regionRoot;
    if (!overlaps(n)) continue;
    if (inRegion && !((e.level < 0 ? e.bound : nodeBound(e.node)) > best + slack)) continue;
    if (n.isLeaf()) {
      // A triangle's bound (its vertices) costs a fraction of f's test: not counted.
      for (std::uint32_t t = n.firstTriangle(); t < n.firstTriangle() + n.triangleCount(); ++t) {
        // f's depth counts at most as the bound: its test may measure depth otherwise (a
        // triangle across a thin box overlaps it on every axis), and a region's best must
        // compare with the bounds it prunes by.
        const double bound = triangleBound(t);
        if (bound > best + slack) {
          best = std::max(best, std::min(bound, static_cast<double>(f(t))));
        }
      }
      continue;
    }
    const std::uint32_t first = n.firstChild();
    if (!inRegion) {
      stack[top++] = Entry{first, e.level + 1, 0.0};
      stack[top++] = Entry{first + 1, e.level + 1, 0.0};
      continue;
    }
    Entry a{first, -1, nodeBound(first)}, b{first + 1, -1, nodeBound(first + 1)};
    if (a.bound > b.bound) std::swap(a, b);  // the deeper one is popped first
    stack[top++] = a;
    stack[top++] = b;
  }
  return visited;
}

}  // namespace adb
