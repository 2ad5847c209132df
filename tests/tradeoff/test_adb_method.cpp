// The ADB-tree shared by the study's ADB and exact methods: built with the settings the
// command line asks for (--exact-counting), once per model.
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

}  // namespace
}  // namespace adb::tradeoff
