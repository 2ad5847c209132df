// Triangles of a tree along a segment: the query behind ray casts and swept-box (convex) casts.
// The segment is walked through the hierarchy nearest node first, and the caller's current
// closest fraction prunes every node entered beyond it, so a ray that hits early touches a
// handful of leaves wherever it points. No allocation, no exception.
//
//   prepare: d = to - from; per axis inverse 1/d (a huge finite value when d is 0 or tiny)
//   push root if the segment meets its (grown) box, with its entry fraction
//   while stack: pop (node, entry); skip when entry > max
//     leaf:  for each triangle: max = min(max, f(triangle))
//     inner: slab-test both children; push the farther, then the nearer (popped first)
#pragma once

#include <algorithm>
#include <cstdint>
#include <utility>

#include "adb/core/geometry.h"
#include "adb/core/detail/segment_walk.h"
#include "adb/core/tree.h"

namespace adb {

/// A point or an axis-aligned box moving along a segment, in mesh coordinates. A node can
/// hold a triangle the mover touches when the segment from -> to meets the node's box grown
/// by the mover's box (Minkowski sum: [lo - sweptHi, hi - sweptLo]) and by the pads.
struct SegmentQuery {
  Vec3 from = Vec3::Zero();
  Vec3 to = Vec3::Zero();
  /// The moving box relative to the moving point (zero for a ray): sweptLo <= sweptHi.
  Vec3 sweptLo = Vec3::Zero();
  Vec3 sweptHi = Vec3::Zero();
  /// Absolute growth of every node box (a contact tolerance, a collision margin), >= 0.
  double pad = 0.0;
  /// Growth of each node box as a fraction of its own largest extent, >= 0: a triangle test
  /// that accepts hits a little outside the triangle (Bullet's ray test accepts 1e-4 of the
  /// triangle's height beyond each edge) reaches that far outside the triangle's box.
  double relativePad = 0.0;
};

/// What a segment query did.
struct SegmentQueryStats {
  std::uint32_t nodes = 0;      ///< node boxes tested against the segment
  std::uint32_t triangles = 0;  ///< triangles handed to the callback
  /// False when the query was refused (a non-finite value, sweptLo > sweptHi, a negative
  /// pad or a NaN max fraction): nothing was visited.
  bool valid = true;
};

/// Calls f(treeTriangle) for every triangle of `tree` in a leaf whose box the query's segment
/// meets (grown as SegmentQuery says) at a fraction in [0, maxFraction], nearest leaf first.
/// f returns the largest fraction still of interest (the closest hit so far, or maxFraction
/// to see everything); nodes entered beyond the smallest value returned so far are skipped.
/// `treeTriangle` indexes tree.triangles(); tree.meshTriangle() maps it to the mesh. Leaves
/// are reported whole: the caller tests the triangles itself. A zero-length segment reports
/// the leaves whose grown box contains the point. No allocation, never throws.
template <typename F>
SegmentQueryStats forEachTriangleAlongSegment(const AdbTree& tree, const SegmentQuery& query,
                                              double maxFraction, F&& f) {
  SegmentQueryStats stats;
  const detail::PreparedSegment s = detail::prepareSegment(tree, query);
  if (!s.valid || !(maxFraction == maxFraction)) {
    stats.valid = false;
    return stats;
  }
  if (maxFraction < 0.0) return stats;
  struct Item {
    std::uint32_t node;
    double entry;
  };
  // A balanced tree over at most 2^28 triangles is at most 29 levels deep (box_query.h):
  // each level leaves at most one pending sibling, so 64 entries cannot overflow.
  Item stack[64];
  int top = 0;
  const auto& nodes = tree.nodes();
  double entry = 0.0;
  ++stats.nodes;
  if (!detail::segmentEntry(s, nodes[0], maxFraction, entry)) return stats;
  stack[top++] = Item{0, entry};
  while (top > 0) {
    const Item item = stack[--top];
    if (item.entry > maxFraction) continue;  // the closest hit so far is nearer
    const Node& n = nodes[item.node];
    if (n.isLeaf()) {
      const std::uint32_t end = n.firstTriangle() + n.triangleCount();
      for (std::uint32_t t = n.firstTriangle(); t < end; ++t) {
        ++stats.triangles;
        const double limit = f(t);
        if (limit < maxFraction) maxFraction = limit;  // a NaN return changes nothing
      }
      continue;
    }
    const std::uint32_t c = n.firstChild();
    double e0 = 0.0, e1 = 0.0;
    stats.nodes += 2;
    const bool hit0 = detail::segmentEntry(s, nodes[c], maxFraction, e0);
    const bool hit1 = detail::segmentEntry(s, nodes[c + 1], maxFraction, e1);
    // The nearer child goes on top: its hits shrink maxFraction before the farther is seen.
    if (hit0 && hit1) {
      if (e0 <= e1) {
        stack[top++] = Item{c + 1, e1};
        stack[top++] = Item{c, e0};
      } else {
        stack[top++] = Item{c, e0};
        stack[top++] = Item{c + 1, e1};
      }
    } else if (hit0) {
      stack[top++] = Item{c, e0};
    } else if (hit1) {
      stack[top++] = Item{c + 1, e1};
    }
  }
  return stats;
}

}  // namespace adb
