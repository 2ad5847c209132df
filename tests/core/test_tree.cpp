// AdbTree structure: every triangle in exactly one leaf, conservative boxes, balanced depth,
// surface statistics, local coordinates, settings validation.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "adb/support/mesh_generators.h"
#include "adb/core/tree.h"
#include "test_support.h"

namespace adb {
namespace {

bool boxContains(const Node& outer, const Vec3& p) {
  return (p.array() >= outer.boxLo().array()).all() && (p.array() <= outer.boxHi().array()).all();
}

void checkStructure(const TriangleMesh& mesh, const AdbTree& tree) {
  const auto& nodes = tree.nodes();
  std::vector<int> seen(mesh.triangleCount(), 0);
  std::vector<int> depth(nodes.size(), 0);
  int maxDepth = 0;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Node& n = nodes[i];
    maxDepth = std::max(maxDepth, depth[i]);
    if (n.isLeaf()) {
      ASSERT_LE(n.triangleCount(), static_cast<unsigned>(tree.settings().maxLeafTriangles));
      for (std::uint32_t t = n.firstTriangle(); t < n.firstTriangle() + n.triangleCount(); ++t) {
        ++seen[tree.meshTriangle(t)];
        for (std::uint32_t v : tree.triangles()[t]) {
          ASSERT_TRUE(boxContains(n, tree.localVertices()[v])) << "leaf " << i;
        }
      }
      continue;
    }
    for (std::uint32_t c = n.firstChild(); c < n.firstChild() + 2; ++c) {
      ASSERT_GT(c, i) << "children come after their parent";
      depth[c] = depth[i] + 1;
      ASSERT_TRUE(boxContains(n, nodes[c].boxLo()) && boxContains(n, nodes[c].boxHi()));
    }
  }
  for (std::size_t t = 0; t < seen.size(); ++t) ASSERT_EQ(seen[t], 1) << "triangle " << t;
  EXPECT_EQ(tree.maxDepth(), maxDepth);
  // SAH splits leave each child at least a tenth of the triangles, and only down to twice a
  // balanced tree's depth (2 L + 2, L = ceil(log2(leaves))); median splits below that take
  // at most L + 1 more levels.
  const double leaves = std::ceil(static_cast<double>(mesh.triangleCount()) /
                                  tree.settings().maxLeafTriangles);
  const int balanced = static_cast<int>(std::ceil(std::log2(std::max(1.0, leaves))));
  EXPECT_LE(maxDepth, 3 * balanced + 3);
}

TEST(TreeStructure, EveryTriangleInExactlyOneLeafAndBoxesNest) {
  for (const TriangleMesh& mesh : {gen::makeTorus(1.0, 0.3, 24, 12), gen::makeSphere(1.0, 2),
                                   gen::makeBox(Vec3(1, 2, 3), 3)}) {
    for (int leaf : {1, 4, 15}) {
      BuildSettings s;
      s.maxLeafTriangles = leaf;
      checkStructure(mesh, AdbTree(mesh, s));
    }
  }
}

TEST(TreeStructure, SingleTriangleMeshIsOneLeaf) {
  TriangleMesh mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
  AdbTree tree(mesh);
  ASSERT_EQ(tree.nodes().size(), 1u);
  EXPECT_TRUE(tree.root().isLeaf());
  EXPECT_EQ(tree.maxDepth(), 0);
}

TEST(TreeStructure, AllCentroidsEqualStillSplitsInHalves) {
  // 64 copies of one triangle: no axis separates them, yet the depth stays logarithmic.
  std::vector<Triangle> tris(64, Triangle{0, 1, 2});
  TriangleMesh mesh({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, tris);
  AdbTree tree(mesh);
  checkStructure(mesh, tree);
}

TEST(TreeLayout, NodeSizesAndMemoryPerTriangle) {
  EXPECT_EQ(sizeof(Node), 32u);
  EXPECT_EQ(sizeof(NodeSurface), 32u);
  EXPECT_EQ(sizeof(NodeOccupancy), 24u);
  const TriangleMesh mesh = gen::makeTorus(1.0, 0.3, 100, 50);  // 10,000 triangles
  AdbTree tree(mesh);
  const double perTriangle = static_cast<double>(tree.memoryBytes()) / static_cast<double>(mesh.triangleCount());
  // Median splits leave ~3 triangles per leaf: ~2n/3 nodes x 120 bytes (Node 32, NodeSurface
  // 32, NodeDistribution 32, NodeOccupancy 24) = 80, + 12 (triangle) + 4 (mesh index) + ~12
  // (half a double vertex) = ~108 bytes; the bound leaves room for vector slack. (115 before
  // the occupancy, which issue 37 added so that slivers cannot be pruned wrongly.)
  EXPECT_LT(perTriangle, 135.0);
}

TEST(TreeSurface, AreasAndNormalsAddUp) {
  const TriangleMesh mesh = gen::makeBox(Vec3(1, 2, 3), 2);
  AdbTree tree(mesh);
  double area = 0.0;
  for (std::size_t t = 0; t < mesh.triangleCount(); ++t) area += mesh.triangleArea(t);
  EXPECT_NEAR(tree.surfaces()[0].area, area, 1e-5 * area);  // stored as float
  // A closed surface's area-weighted normals cancel.
  EXPECT_LT(tree.surfaces()[0].coherence, 1e-5);
  const TriangleMesh flat = gen::makeFlatGrid(2.0, 2.0, 8, 8);
  AdbTree flatTree(flat);
  for (const NodeSurface& s : flatTree.surfaces()) {
    EXPECT_NEAR(s.coherence, 1.0, 1e-6);
    EXPECT_NEAR(std::abs(s.normal[2]), 1.0, 1e-6);
  }
}

TEST(TreeSettings, InvalidSettingsAreRejectedWithTheirName) {
  const TriangleMesh mesh = gen::makeSphere(1.0, 1);
  BuildSettings s;
  s.gridResolution = 0;
  EXPECT_THROW({ AdbTree t(mesh, s); }, SettingsError);
  s.gridResolution = 33;
  try {
    AdbTree t(mesh, s);
    FAIL();
  } catch (const SettingsError& e) {
    EXPECT_NE(std::string(e.what()).find("gridResolution"), std::string::npos);
  }
  s = BuildSettings{};
  s.maxLeafTriangles = 16;
  EXPECT_THROW({ AdbTree t(mesh, s); }, SettingsError);
}

TEST(TreeFrame, FarFromOriginKeepsLocalPrecision) {
  // The same sphere at the origin and 1e5 away: local coordinates agree to double rounding of
  // the shift, and the float boxes are identical up to a few ulps of the local size.
  const TriangleMesh near = gen::makeSphere(1.0, 2);
  const TriangleMesh far = gen::transformed(near, Pose{Mat3::Identity(), Vec3(1e5, -1e5, 1e5)});
  AdbTree a(near), b(far);
  EXPECT_NEAR((b.origin() - a.origin() - Vec3(1e5, -1e5, 1e5)).norm(), 0.0, 1e-9);
  ASSERT_EQ(a.nodes().size(), b.nodes().size());
  for (std::size_t i = 0; i < a.nodes().size(); ++i) {
    EXPECT_NEAR((a.nodes()[i].boxLo() - b.nodes()[i].boxLo()).norm(), 0.0, 1e-6);
    EXPECT_NEAR(a.nodes()[i].pc, b.nodes()[i].pc, 1e-3);
  }
}

}  // namespace
}  // namespace adb
