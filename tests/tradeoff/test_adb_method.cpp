// The ADB-trees shared by the study's ADB and exact methods: built with the settings the
// command line asks for (--exact-counting), once per model, two for a pair of models.
#include <gtest/gtest.h>

#include "adb/support/mesh_generators.h"
#include "adb_method.h"

namespace adb::tradeoff {
namespace {

TEST(SharedTree, BuildsWithTheCellCountingItIsGiven) {
  const Model model{"knot", 0, gen::makeModel("knot", 1000)};
  SharedTree approximate;
  EXPECT_EQ(approximate.treeFor(model).settings().counting, CellCounting::Approximate);

  BuildSettings exactCounts;
  exactCounts.counting = CellCounting::Exact;
  SharedTree exact(exactCounts);
  const AdbTree& tree = exact.treeFor(model);
  EXPECT_EQ(tree.settings().counting, CellCounting::Exact);
  EXPECT_EQ(&exact.treeFor(model), &tree);  // the same model: built once
}

// A pair of models: both trees held, each built once, and the trees of the next case replace
// them (a model is known by its key, Model::index).
TEST(SharedTree, HoldsTheTwoTreesOfAPair) {
  const Model knot{"knot", 0, gen::makeModel("knot", 1000)};
  const Model torus{"torus", 1, gen::makeModel("torus", 1000)};
  SharedTree shared;
  shared.prepare(knot, torus);
  const AdbTree& a = shared.treeFor(knot);
  const AdbTree& b = shared.treeFor(torus);
  EXPECT_NE(&a, &b);
  EXPECT_EQ(a.triangles().size(), knot.mesh.triangleCount());
  EXPECT_EQ(b.triangles().size(), torus.mesh.triangleCount());
  shared.prepare(knot, torus);  // a second method of the same case: nothing rebuilt
  EXPECT_EQ(&shared.treeFor(knot), &a);
  EXPECT_EQ(&shared.treeFor(torus), &b);

  const Model sphere{"sphere", 2, gen::makeModel("sphere", 1000)};
  shared.prepare(sphere, sphere);  // the next case: one model against itself
  EXPECT_EQ(shared.treeFor(sphere).triangles().size(), sphere.mesh.triangleCount());
}

}  // namespace
}  // namespace adb::tradeoff
