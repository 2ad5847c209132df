// Uses the installed core: builds a tree and answers one query.
#include <adb/core/mesh_generators.h>
#include <adb/core/query.h>
#include <adb/core/tree.h>

#include <cstdio>

int main() {
  const adb::TriangleMesh mesh = adb::gen::makeTorus(1.0, 0.3, 32, 16);
  const adb::AdbTree tree(mesh);
  adb::QueryScratch scratch;
  adb::QuerySettings exact;
  exact.mode = adb::QueryMode::Exact;
  const adb::Pose moved{adb::Mat3::Identity(), adb::Vec3(0.5, 0.0, 0.0)};
  const adb::QueryResult r = adb::collide(tree, adb::Pose{}, tree, moved, exact, scratch);
  std::printf("collides %d\n", r.collides ? 1 : 0);
  return r.collides ? 0 : 1;
}
