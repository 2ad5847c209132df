// The README's core API snippet, compiled and run as a test so that it never goes stale.
#include <gtest/gtest.h>

// --- README snippet begins ---
#include <adb/core/query.h>
#include <adb/core/tree.h>
#include <adb/support/mesh_generators.h>  // generated test geometry (adb::support)

bool readmeExample() {
  // Any indexed triangle mesh: validated here (adb::MeshError names a bad vertex/triangle).
  adb::TriangleMesh mesh = adb::gen::makeTorusKnot(2, 3, 1.0, 0.25, 256, 16);
  adb::AdbTree tree(mesh);  // AABB tree + possible-collision-cell counts, built once

  adb::Pose a;  // world = rotation * x + translation
  adb::Pose b{Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix(),
              Eigen::Vector3d(0.8, 0.0, 0.0)};

  adb::QuerySettings settings;  // ADB mode, p_min 0.99, k_min 10 (the paper's defaults)
  settings.budgetNodePairs = 5000;  // optional: a work budget (reproducible), or
  // settings.budgetMicros = 50;     // a wall-clock one; either way the result says how sure
  adb::QueryScratch scratch;    // one per thread; reused, so queries do not allocate

  adb::QueryResult r = adb::collide(tree, a, tree, b, settings, scratch);
  // r.collides, r.confidence in [0, 1], r.stop (why it stopped), r.nodePairs, r.seconds,
  // scratch.witnesses(): the node or triangle pairs behind a "collision".
  return r.collides && r.confidence > 0.5;
}
// --- README snippet ends ---

TEST(Readme, CoreSnippetRuns) { EXPECT_TRUE(readmeExample()); }
