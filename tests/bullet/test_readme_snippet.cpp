// The README's Bullet snippet, compiled and run as a test so that it never goes stale.
#include <gtest/gtest.h>

#include <adb/core/mesh_generators.h>

// --- README snippet begins ---
#include <adb/bullet/mesh_mesh_algorithm.h>
#include <adb/bullet/mesh_shape.h>

bool readmeBulletExample() {
  btDefaultCollisionConfiguration configuration(adb::collisionConstructionInfo());
  btCollisionDispatcher dispatcher(&configuration);
  adb::registerAlgorithms(dispatcher, configuration);  // MeshShape pairs, contacts + closest points

  auto mesh = adb::MeshData::build(adb::gen::makeTorus(0.35, 0.12, 48, 24));  // or your mesh
  adb::MeshShape shape(mesh);  // many bodies may share `mesh`
  // --- README snippet ends ---
  return shape.getShapeType() == CUSTOM_CONCAVE_SHAPE_TYPE &&
         dispatcher.getNumManifolds() == 0;
}

TEST(Readme, BulletSnippetRuns) { EXPECT_TRUE(readmeBulletExample()); }
