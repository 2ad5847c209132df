// The occupancy of every node (node_occupancy.h): for each triangle below a node, the cells
// of the node's grid that its box spans, each kept only when the triangle meets the cell grown
// by the margins (separating axes, Akenine-Moller's triangle-box test). A triangle in one cell,
// as most are below a node many times its size, costs no test.
#include "node_occupancy.h"

#include <algorithm>

#include "tree_builder.h"

namespace adb::detail {
namespace {

// A triangle's separating axes against boxes of one size (a node's cells): the triangle's
// normal and the 9 cross products of its edges with the box axes, each with the interval of
// the triangle's projection and the box's projected radius, so that a cell costs a dot
// product per axis (Akenine-Moller's triangle-box test with the box's face axes left to the
// caller, which only asks for cells within the triangle's box). A degenerate triangle has
// zero axes among them, which separate nothing: the test is then conservative.
struct TriangleAxes {
  Vec3 axis[10];
  double lo[10], hi[10], radius[10];

  TriangleAxes(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& half) {
    const Vec3 edges[3] = {b - a, c - b, a - c};
    axis[0] = edges[0].cross(edges[1]);
    for (int e = 0; e < 3; ++e) {
      for (int k = 0; k < 3; ++k) axis[1 + 3 * e + k] = edges[e].cross(Vec3::Unit(k));
    }
    for (int i = 0; i < 10; ++i) {
      const double p0 = axis[i].dot(a), p1 = axis[i].dot(b), p2 = axis[i].dot(c);
      lo[i] = std::min({p0, p1, p2});
      hi[i] = std::max({p0, p1, p2});
      radius[i] = half.dot(axis[i].cwiseAbs());
    }
  }

  // Whether the triangle meets the box centred at `centre` (half extents as constructed).
  bool meetsBoxAt(const Vec3& centre) const {
    for (int i = 0; i < 10; ++i) {
      const double d = axis[i].dot(centre);
      if (lo[i] - d > radius[i] || hi[i] - d < -radius[i]) return false;
    }
    return true;
  }
};

// The cells of node n (layout o) that triangle a, b, c touches.
std::uint64_t cellsTouched(const Node& n, const NodeOccupancy& o, const Vec3& a, const Vec3& b,
                           const Vec3& c) {
  const Vec3 lo = n.boxLo();
  const double absolute = kBuildRelativeMargin * (n.boxHi() - lo).maxCoeff();
  const Vec3 tLo = a.cwiseMin(b).cwiseMin(c), tHi = a.cwiseMax(b).cwiseMax(c);
  int from[3], to[3];
  Vec3 width, half;  // of a slice (0 along a flat axis), and of a cell grown by the margins
  for (int k = 0; k < 3; ++k) {
    const int slices = 1 << o.shift[k];
    const double scale = o.scale[k];
    width[k] = scale > 0.0 ? 1.0 / scale : 0.0;
    // A slice's bounds from its index, grown beyond anything a query's margin reaches.
    half[k] = 0.5 * width[k] + kBuildSliceMargin * width[k] + absolute;
    from[k] = occupancySlice((tLo[k] - lo[k]) * scale - kBuildSliceMargin, slices, 0);
    to[k] = occupancySlice((tHi[k] - lo[k]) * scale + kBuildSliceMargin, slices, slices - 1);
  }
  if (from[0] == to[0] && from[1] == to[1] && from[2] == to[2]) {
    return occupancyCells(o, from, to);
  }
  const TriangleAxes axes(a, b, c, half);
  std::uint64_t cells = 0;
  int at[3];
  for (at[2] = from[2]; at[2] <= to[2]; ++at[2]) {
    for (at[1] = from[1]; at[1] <= to[1]; ++at[1]) {
      for (at[0] = from[0]; at[0] <= to[0]; ++at[0]) {
        const Vec3 centre(lo[0] + (at[0] + 0.5) * width[0], lo[1] + (at[1] + 0.5) * width[1],
                          lo[2] + (at[2] + 0.5) * width[2]);
        if (axes.meetsBoxAt(centre)) cells |= occupancyCells(o, at, at);
      }
    }
  }
  return cells;
}

// Above this many triangles a node's cells are those its children's cells reach: a triangle
// small against the node's cells (as most are, that high) falls in one cell either way, and
// testing every triangle at every level made the build 10 times slower (`adb-bench-core
// --benchmark_filter=BM_BuildApproximate`: 0.05 -> 0.5 s at 100k triangles; 0.31 s per 100k
// with this, SAH and the cells together). The children's cells are grown by the margins, so
// the union stays conservative; it is a little looser than the triangles' own.
constexpr std::uint32_t kTrianglesTestedDirectly = 64;

// The cells of node n (layout o) that the occupied cells of its child reach.
std::uint64_t cellsOfChild(const Node& n, const NodeOccupancy& o, const Node& child,
                           const NodeOccupancy& co) {
  if (co.cells == 0) return 0;
  const Vec3 lo = n.boxLo(), childLo = child.boxLo();
  const double absolute = kBuildRelativeMargin * (child.boxHi() - childLo).maxCoeff();
  // Per axis, the parent's slices that each child slice reaches.
  int from[3][64], to[3][64];
  for (int k = 0; k < 3; ++k) {
    const int slices = 1 << co.shift[k], parentSlices = 1 << o.shift[k];
    const double width = co.scale[k] > 0.0f ? 1.0 / co.scale[k] : 0.0;
    const double grow = kBuildSliceMargin * width + absolute;
    for (int i = 0; i < slices; ++i) {
      const double sliceLo = childLo[k] + i * width - grow;
      const double sliceHi = childLo[k] + (i + 1) * width + grow;
      from[k][i] =
          occupancySlice((sliceLo - lo[k]) * o.scale[k] - kBuildSliceMargin, parentSlices, 0);
      to[k][i] = occupancySlice((sliceHi - lo[k]) * o.scale[k] + kBuildSliceMargin, parentSlices,
                                parentSlices - 1);
    }
  }
  const int sx = co.shift[0], sxy = co.shift[0] + co.shift[1];
  std::uint64_t cells = 0;
  for (std::uint64_t bits = co.cells; bits != 0; bits &= bits - 1) {
    const int bit = __builtin_ctzll(bits);
    const int x = bit & ((1 << sx) - 1), y = (bit >> sx) & ((1 << co.shift[1]) - 1), z = bit >> sxy;
    const int f[3] = {from[0][x], from[1][y], from[2][z]}, t[3] = {to[0][x], to[1][y], to[2][z]};
    cells |= occupancyCells(o, f, t);
  }
  return cells;
}

// Per node, the sum of its triangles' squared longest edges, children first (sums add up the
// tree, as NodeSurface::area does): with the area, whether the node is slivers
// (kSliverFatness), without visiting every triangle again at every level.
std::vector<double> longestEdgesSquared(const AdbTree& tree) {
  const auto& nodes = tree.nodes();
  const auto& verts = tree.localVertices();
  const auto& tris = tree.triangles();
  std::vector<double> sum(nodes.size(), 0.0);
  for (std::size_t i = nodes.size(); i-- > 0;) {
    const Node& n = nodes[i];
    if (!n.isLeaf()) {
      sum[i] = sum[n.firstChild()] + sum[n.firstChild() + 1];
      continue;
    }
    for (std::uint32_t t = n.firstTriangle(); t < n.firstTriangle() + n.triangleCount(); ++t) {
      const Vec3 &a = verts[tris[t][0]], &b = verts[tris[t][1]], &c = verts[tris[t][2]];
      sum[i] += std::max({(b - a).squaredNorm(), (c - b).squaredNorm(), (a - c).squaredNorm()});
    }
  }
  return sum;
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
  const std::vector<double> longest = longestEdgesSquared(tree);
  auto& occupancy = TreeBuilderAccess::occupancy(tree);
  occupancy.resize(nodes.size());
  // Children first (a child's index is above its parent's).
  for (std::size_t i = nodes.size(); i-- > 0;) {
    const Node& n = nodes[i];
    NodeOccupancy o = occupancyLayout(n.boxHi() - n.boxLo());
    o.cells = 0;
    o.triangles = std::min<std::uint32_t>(ranges[i].second - ranges[i].first, 127) & 0x7Fu;
    o.slivers = tree.surfaces()[i].area < kSliverFatness * longest[i] ? 1 : 0;
    if (n.isLeaf() || ranges[i].second - ranges[i].first <= kTrianglesTestedDirectly) {
      for (std::uint32_t t = ranges[i].first; t < ranges[i].second && o.cells != ~0ull; ++t) {
        o.cells |= cellsTouched(n, o, verts[tris[t][0]], verts[tris[t][1]], verts[tris[t][2]]);
      }
    } else {
      for (std::uint32_t c = n.firstChild(); c <= n.firstChild() + 1; ++c) {
        o.cells |= cellsOfChild(n, o, nodes[c], occupancy[c]);
      }
    }
    occupancy[i] = o;
  }
}

}  // namespace adb::detail
