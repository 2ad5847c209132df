// Uses the installed package: the README's three Bullet lines and a torus dropped on a mesh
// ground under a per-step budget; the core (a tree, one query); io (writes a small OBJ into
// the directory given as argument, else the system's temporary directory, and loads it).
#include <adb/bullet/dispatcher.h>
#include <adb/bullet/mesh_shape.h>
#include <adb/support/mesh_generators.h>
#include <adb/core/query.h>
#include <adb/core/tree.h>
#include <adb/io/mesh_file.h>

#include <btBulletDynamicsCommon.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

namespace {

// A torus dropped on a mesh ground for 2 s: true when it rests above the ground.
bool bulletApplicationRuns() {
  btDefaultCollisionConfiguration configuration(adb::collisionConstructionInfo());
  adb::Dispatcher dispatcher(&configuration);
  adb::FrameSettings budget;
  budget.budgetMicros = 2000;
  dispatcher.setFrameSettings(budget);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world(&dispatcher, &broadphase, &solver, &configuration);
  world.setGravity(btVector3(0, -10, 0));
  adb::MeshShape ground(adb::MeshData::build(adb::gen::makeBox(adb::Vec3(5, 0.5, 5), 2)));
  adb::MeshShape torus(adb::MeshData::build(adb::gen::makeTorus(0.35, 0.12, 32, 16)));
  btRigidBody floor(btRigidBody::btRigidBodyConstructionInfo(0, nullptr, &ground));
  floor.getWorldTransform().setOrigin(btVector3(0, btScalar(-0.5), 0));
  btVector3 inertia;
  torus.calculateLocalInertia(1, inertia);
  btRigidBody body(btRigidBody::btRigidBodyConstructionInfo(1, nullptr, &torus, inertia));
  body.getWorldTransform().setOrigin(btVector3(0, 1, 0));
  world.addRigidBody(&floor);
  world.addRigidBody(&body);
  for (int i = 0; i < 120; ++i) world.stepSimulation(btScalar(1.0 / 60), 1, btScalar(1.0 / 60));
  const double y = body.getWorldTransform().getOrigin().y();
  world.removeRigidBody(&body);
  world.removeRigidBody(&floor);
  std::printf("torus rests at y = %.3f\n", y);
  return y > 0.0 && y < 0.5;
}

}  // namespace

int main(int argc, char** argv) {
  const bool bullet = bulletApplicationRuns();
  const adb::TriangleMesh mesh = adb::gen::makeTorus(1.0, 0.3, 32, 16);
  const adb::AdbTree tree(mesh);
  adb::QueryScratch scratch;
  adb::QuerySettings exact;
  exact.mode = adb::QueryMode::Exact;
  const adb::Pose moved{adb::Mat3::Identity(), adb::Vec3(0.5, 0.0, 0.0)};
  const adb::QueryResult r = adb::collide(tree, adb::Pose{}, tree, moved, exact, scratch);
  std::printf("collides %d\n", r.collides ? 1 : 0);

  const std::filesystem::path dir =
      argc > 1 ? std::filesystem::path(argv[1]) : std::filesystem::temp_directory_path();
  const std::string file = (dir / "adb_consumer_quad.obj").string();
  std::ofstream(file) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
  adb::io::LoadReport report;
  const adb::TriangleMesh quad = adb::io::loadMesh(file, &report);
  std::filesystem::remove(file);
  std::printf("loaded %zu triangles\n", quad.triangleCount());
  return bullet && r.collides && quad.triangleCount() == 2 ? 0 : 1;
}
