// Internal to adb/core/box_query.h: the tree walk its queries share and the box and slab
// bounds they test. A header only because the queries are templates over the caller's
// callback (inlined into the hot loop); not part of the API.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <utility>

#include "adb/core/geometry.h"
#include "adb/core/tree.h"

namespace adb::detail {

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

/// Whether a node's box (tree-local) overlaps an oriented box, on the 6 face axes of the
/// two boxes (conservative: the 9 edge axes would prune a few more).
struct OrientedBoxOverlap {
  Vec3 centre;  // tree-local
  Mat3 axes;
  Mat3 absAxes;
  Vec3 half;
  Vec3 extent;  // its half extents along the tree's axes

  OrientedBoxOverlap(const Vec3& localCentre, const Mat3& boxAxes, const Vec3& boxHalf)
      : centre(localCentre), axes(boxAxes), absAxes(boxAxes.cwiseAbs()), half(boxHalf),
        extent(absAxes * boxHalf) {}

  bool operator()(const Node& n) const {
    const Vec3 nodeHalf = 0.5 * (n.boxHi() - n.boxLo());
    const Vec3 offset = centre - 0.5 * (n.boxHi() + n.boxLo());
    if ((offset.cwiseAbs().array() > (nodeHalf + extent).array()).any()) return false;
    const Vec3 along = axes.transpose() * offset;  // on the oriented box's axes
    return !(along.cwiseAbs().array() > (half + absAxes.transpose() * nodeHalf).array()).any();
  }
};

/// The range of a . (x - origin) over the node's box cut by its slab (tree-local): the box's
/// range meets the range the slab allows, a . x = (a . n)(n . x) + a_perp . x with n . x
/// within the slab and a_perp . x within the box. Why the slab: a flat patch tilted in the
/// mesh frame has boxes much deeper than its triangles; its slab is as thin as the patch.
inline std::pair<double, double> rangeAlong(const Node& n, const NodeDistribution& d,
                                            const Vec3& a, const Vec3& origin) {
  const Vec3 half = 0.5 * (n.boxHi() - n.boxLo());
  const Vec3 centre = 0.5 * (n.boxHi() + n.boxLo()) - origin;
  const double boxMid = a.dot(centre), boxHalf = a.cwiseAbs().dot(half);
  const Vec3 normal(d.normal[0], d.normal[1], d.normal[2]);
  const double along = a.dot(normal);
  const Vec3 across = a - along * normal;
  const double slabMid =
      along * (static_cast<double>(d.offset) - normal.dot(origin)) + across.dot(centre);
  const double slabHalf =
      std::abs(along) * static_cast<double>(d.halfWidth) + across.cwiseAbs().dot(half);
  return {std::max(boxMid - boxHalf, slabMid - slabHalf),
          std::min(boxMid + boxHalf, slabMid + slabHalf)};
}

/// An upper bound on how deep a point of the node can lie inside `solid` (tree-local): a
/// point's depth is at most its distance to each pair of faces, min_k (half_k - |q_k|).
inline double deepestPossible(const Node& n, const NodeDistribution& d,
                              const OrientedBox& solid) {
  double deepest = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const auto [lo, hi] = rangeAlong(n, d, solid.axes.col(k), solid.centre);
    const double nearest = std::max({0.0, lo, -hi});
    deepest = std::min(deepest, solid.half[k] - nearest);
  }
  return deepest;
}

}  // namespace adb::detail
