// The occupied cells of a node (node_occupancy.h): a bounding volume that must hold every point
// of every triangle below the node (the proof the traversal relies on), and that is tight
// where boxes are not (a diagonal sliver).
#include <gtest/gtest.h>

#include <bitset>
#include <random>

#include "adb/support/mesh_generators.h"
#include "adb/core/tree.h"
#include "node_occupancy.h"
#include "test_support.h"
#include "tree_builder.h"

namespace adb {
namespace {

int cellCount(std::uint64_t cells) { return static_cast<int>(std::bitset<64>(cells).count()); }

// Every vertex, edge point and random interior point of every triangle below every node
// lies in an occupied cell of that node (queried as a point box, with no margin of its own).
void expectEveryPointOccupied(const TriangleMesh& mesh) {
  const AdbTree tree(mesh);
  const auto ranges = detail::triangleRanges(tree);
  const auto& verts = tree.localVertices();
  std::mt19937_64 rng(test::kSeed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  long checked = 0, missed = 0;
  for (std::size_t i = 0; i < tree.nodes().size(); ++i) {
    const Node& n = tree.nodes()[i];
    const NodeOccupancy& o = tree.occupancy()[i];
    for (std::uint32_t t = ranges[i].first; t < ranges[i].second; ++t) {
      const Vec3& a = verts[tree.triangles()[t][0]];
      const Vec3& b = verts[tree.triangles()[t][1]];
      const Vec3& c = verts[tree.triangles()[t][2]];
      for (int k = 0; k < 12; ++k) {
        double x = u(rng), y = u(rng);
        if (k < 3) x = k == 1, y = k == 2;                 // the vertices
        else if (k < 6) y = 0.0;                           // points of edge ab
        else if (x + y > 1.0) x = 1.0 - x, y = 1.0 - y;    // inside
        const Vec3 p = a + x * (b - a) + y * (c - a);
        ++checked;
        missed += detail::occupiedWithin(n, o, p, p) ? 0 : 1;
      }
    }
  }
  EXPECT_EQ(missed, 0) << "of " << checked << " points";
}

TEST(NodeOccupancy, EveryPointOfEveryTriangleLiesInAnOccupiedCell) {
  expectEveryPointOccupied(gen::makeCylinder(0.3, 2.0, 48, 1, 1));  // slivers, 51:1
  expectEveryPointOccupied(gen::makeTorusKnot(2, 3, 1.0, 0.2, 64, 8));
  expectEveryPointOccupied(gen::makeFlatGrid(2.0, 1.0, 7, 3));  // flat nodes: 8 x 8 x 1 cells
  expectEveryPointOccupied(gen::transformed(gen::makeBox(Vec3(1e-4, 2e-4, 3e-4), 2),
                                            Pose{Mat3::Identity(), Vec3(1e4, -1e4, 5e3)}));
}

TEST(NodeOccupancy, ALongDiagonalSliverFillsFewOfItsBoxsCells) {
  // One triangle from corner to corner of a 2 x 2 x 2 box, 0.01 wide: its box is the whole
  // cube, its cells a thin diagonal band.
  const TriangleMesh sliver({{-1, -1, -1}, {1, 1, 1}, {1.01, 0.99, 1}}, {{0, 1, 2}});
  const AdbTree tree(sliver);
  // Of 64: the 4 on the diagonal and, as the diagonal runs through the grid's 3 inner
  // corners, the cells sharing them (a touch counts).
  EXPECT_LE(cellCount(tree.occupancy()[0].cells), 24);
  EXPECT_GE(cellCount(tree.occupancy()[0].cells), 4);
  // A point in the cube far from the diagonal holds none of it; the centre does.
  const Node& n = tree.root();
  EXPECT_FALSE(detail::occupiedWithin(n, tree.occupancy()[0], Vec3(0.8, -0.8, -0.8),
                                      Vec3(0.9, -0.7, -0.7)));
  EXPECT_TRUE(detail::occupiedWithin(n, tree.occupancy()[0], Vec3::Zero(), Vec3::Zero()));
  // An empty box holds nothing, a box round the node everything.
  EXPECT_FALSE(detail::occupiedWithin(n, tree.occupancy()[0], Vec3::Ones(), -Vec3::Ones()));
  EXPECT_TRUE(detail::occupiedWithin(n, tree.occupancy()[0], Vec3::Constant(-5),
                                     Vec3::Constant(5)));
}

TEST(NodeOccupancy, CellsAreNearCubic) {
  const auto slices = [](const Vec3& extent) {
    const NodeOccupancy o = detail::occupancyLayout(extent);
    return std::array<int, 3>{1 << o.shift[0], 1 << o.shift[1], 1 << o.shift[2]};
  };
  EXPECT_EQ(slices(Vec3(1, 1, 1)), (std::array<int, 3>{4, 4, 4}));
  EXPECT_EQ(slices(Vec3(2, 2, 0)), (std::array<int, 3>{8, 8, 1}));      // flat
  EXPECT_EQ(slices(Vec3(0, 5, 0)), (std::array<int, 3>{1, 64, 1}));     // a segment
  EXPECT_EQ(slices(Vec3(4, 1, 1)), (std::array<int, 3>{16, 2, 2}));
  EXPECT_EQ(slices(Vec3(0, 0, 0)), (std::array<int, 3>{64, 1, 1}));     // a point: one cell
  const NodeOccupancy point = detail::occupancyLayout(Vec3::Zero());
  EXPECT_EQ(point.scale[0], 0.0f);  // every coordinate maps to slice 0
}

TEST(NodeOccupancy, CellMasksCoverExactlyTheSlicesAsked) {
  NodeOccupancy o = detail::occupancyLayout(Vec3(4, 2, 2));  // 8 x 4 x 2 slices
  ASSERT_EQ(o.shift[0] + o.shift[1] + o.shift[2], 6);
  const int from[3] = {2, 1, 0}, to[3] = {5, 2, 1};
  const std::uint64_t mask = detail::occupancyCells(o, from, to);
  const int nx = 1 << o.shift[0], ny = 1 << o.shift[1];
  for (int bit = 0; bit < 64; ++bit) {
    const int x = bit % nx, y = (bit / nx) % ny, z = bit / (nx * ny);
    const bool inside = x >= from[0] && x <= to[0] && y >= from[1] && y <= to[1] &&
                        z >= from[2] && z <= to[2];
    EXPECT_EQ(((mask >> bit) & 1u) != 0, inside) << "bit " << bit;
  }
  const int all[3] = {nx - 1, ny - 1, (1 << o.shift[2]) - 1}, none[3] = {0, 0, 0};
  EXPECT_EQ(detail::occupancyCells(o, none, all), ~0ull);
}

}  // namespace
}  // namespace adb
