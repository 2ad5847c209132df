// The occupancy of every node (node_occupancy.h): for each triangle below a node, the cells
// of the node's grid that its box spans, each kept only when the triangle meets the cell grown
// by the margins (separating axes, Akenine-Moller's triangle-box test). A triangle in one cell,
// as most are below a node many times its size, costs no test.
#include "node_occupancy.h"

#include <algorithm>
#include <array>

#include "tree_builder.h"

namespace adb::detail {
namespace {

// Whether the triangle's projection on `axis` meets the box's, the box centred at the origin
// with half extents h (the triangle relative to it).
bool overlapOnAxis(const Vec3& axis, const std::array<Vec3, 3>& v, const Vec3& h) {
  const double p0 = axis.dot(v[0]), p1 = axis.dot(v[1]), p2 = axis.dot(v[2]);
  const double r = h.dot(axis.cwiseAbs());
  return !(std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r);
}

// Triangle a, b, c against the box [lo, hi], touching included: the box's 3 face axes, the
// triangle's normal and the 9 cross products of edges and box axes. A degenerate triangle has
// zero axes among them, which separate nothing: the test is then conservative.
bool triangleMeetsBox(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& lo,
                      const Vec3& hi) {
  const Vec3 centre = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
  const std::array<Vec3, 3> v = {a - centre, b - centre, c - centre};
  for (int k = 0; k < 3; ++k) {
    const double mn = std::min({v[0][k], v[1][k], v[2][k]});
    const double mx = std::max({v[0][k], v[1][k], v[2][k]});
    if (mn > h[k] || mx < -h[k]) return false;
  }
  const std::array<Vec3, 3> edges = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  if (!overlapOnAxis(edges[0].cross(edges[1]), v, h)) return false;
  for (const Vec3& e : edges) {
    for (int k = 0; k < 3; ++k) {
      if (!overlapOnAxis(e.cross(Vec3::Unit(k)), v, h)) return false;
    }
  }
  return true;
}

// The cells of node n (layout o) that triangle a, b, c touches.
std::uint64_t cellsTouched(const Node& n, const NodeOccupancy& o, const Vec3& a, const Vec3& b,
                           const Vec3& c) {
  const Vec3 lo = n.boxLo();
  const double absolute = kBuildRelativeMargin * (n.boxHi() - lo).maxCoeff();
  const Vec3 tLo = a.cwiseMin(b).cwiseMin(c), tHi = a.cwiseMax(b).cwiseMax(c);
  int from[3], to[3];
  Vec3 width;  // of a slice (0 along a flat axis)
  for (int k = 0; k < 3; ++k) {
    const int slices = 1 << o.shift[k];
    const double scale = o.scale[k];
    width[k] = scale > 0.0 ? 1.0 / scale : 0.0;
    from[k] = occupancySlice((tLo[k] - lo[k]) * scale - kBuildSliceMargin, slices, 0);
    to[k] = occupancySlice((tHi[k] - lo[k]) * scale + kBuildSliceMargin, slices, slices - 1);
  }
  if (from[0] == to[0] && from[1] == to[1] && from[2] == to[2]) {
    return occupancyCells(o, from, to);
  }
  std::uint64_t cells = 0;
  int at[3];
  for (at[2] = from[2]; at[2] <= to[2]; ++at[2]) {
    for (at[1] = from[1]; at[1] <= to[1]; ++at[1]) {
      for (at[0] = from[0]; at[0] <= to[0]; ++at[0]) {
        Vec3 cellLo, cellHi;
        for (int k = 0; k < 3; ++k) {
          // A slice's bounds from its index, grown beyond anything a query's margin reaches.
          const double grow = kBuildSliceMargin * width[k] + absolute;
          cellLo[k] = lo[k] + at[k] * width[k] - grow;
          cellHi[k] = lo[k] + (at[k] + 1) * width[k] + grow;
        }
        if (triangleMeetsBox(a, b, c, cellLo, cellHi)) cells |= occupancyCells(o, at, at);
      }
    }
  }
  return cells;
}

}  // namespace

NodeOccupancy occupancyLayout(const Vec3& extent) {
  NodeOccupancy o{};
  int shift[3] = {0, 0, 0};
  for (int doubling = 0; doubling < 6; ++doubling) {
    int widest = 0;
    for (int k = 1; k < 3; ++k) {
      if (extent[k] / (1 << shift[k]) > extent[widest] / (1 << shift[widest])) widest = k;
    }
    ++shift[widest];
  }
  for (int k = 0; k < 3; ++k) {
    o.shift[k] = static_cast<std::uint8_t>(shift[k]);
    // A flat axis (never split, as a split goes to a wider one) maps to slice 0.
    o.scale[k] = extent[k] > 0.0 ? static_cast<float>((1 << shift[k]) / extent[k]) : 0.0f;
  }
  return o;
}

void computeOccupancy(AdbTree& tree) {
  const auto& nodes = tree.nodes();
  const auto& verts = tree.localVertices();
  const auto& tris = tree.triangles();
  const auto ranges = triangleRanges(tree);
  auto& occupancy = TreeBuilderAccess::occupancy(tree);
  occupancy.resize(nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Node& n = nodes[i];
    NodeOccupancy o = occupancyLayout(n.boxHi() - n.boxLo());
    o.cells = 0;
    for (std::uint32_t t = ranges[i].first; t < ranges[i].second && o.cells != ~0ull; ++t) {
      o.cells |= cellsTouched(n, o, verts[tris[t][0]], verts[tris[t][1]], verts[tris[t][2]]);
    }
    occupancy[i] = o;
  }
}

}  // namespace adb::detail
