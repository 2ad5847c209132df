// adb-bench-pairs: the time of each mesh-convex pair kind, adb's algorithm against Bullet's
// btConvexConcaveCollisionAlgorithm on a btBvhTriangleMeshShape of the same mesh.
//   build/bin/adb-bench-pairs                                  # every kind, both sides
//   build/bin/adb-bench-pairs --benchmark_filter=wall
// Each iteration places the two bodies at the next of 64 seeded poses (the convex shape
// resting on the mesh's surface) and runs the world's collision detection once: broadphase,
// dispatch and contacts, the same work on both sides. The ratio of the two lines is the
// figure (docs/bullet-results.md); counters report contacts and depth per pose, so that a
// fast answer with no contacts would show.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "adb/support/mesh_generators.h"
#include "shared/pair_kind_scene.h"

namespace {

using adb::tools::ConvexKind;

constexpr int kPoses = 64;

// A 20k-triangle torus knot: a CAD-sized concave mesh with surface in every direction.
const adb::TriangleMesh& knot() {
  static const adb::TriangleMesh mesh = adb::gen::makeModel("knot", 20000);
  return mesh;
}

void pairKind(benchmark::State& state, ConvexKind kind, bool adb) {
  const auto world = adb::tools::makePairWorld(knot(), kind, adb);
  const auto poses = adb::tools::surfacePoses(
      knot(), static_cast<const btConvexShape&>(*world->convexShape), kind, kPoses, 7);
  std::size_t i = 0;
  for (auto _ : state) {
    const auto& [meshPose, convexPose] = poses[i++ % poses.size()];
    world->collide(meshPose, convexPose);
  }
  // Outside the timing: what the contacts were, pose by pose.
  double points = 0.0, deepest = 0.0;
  for (const auto& [meshPose, convexPose] : poses) {
    world->collide(meshPose, convexPose);
    points += world->contactPoints();
    deepest += world->deepestPenetration();
  }
  state.counters["contacts"] = points / kPoses;
  state.counters["depth"] = deepest / kPoses;
}

void registerAll() {
  for (ConvexKind kind : {ConvexKind::Box, ConvexKind::Wall, ConvexKind::Sphere,
                          ConvexKind::Capsule, ConvexKind::Cylinder, ConvexKind::Hull}) {
    for (bool adb : {true, false}) {
      const std::string name = std::string("pair/") + adb::tools::kindName(kind) +
                               (adb ? "/adb" : "/bullet");
      benchmark::RegisterBenchmark(name.c_str(), pairKind, kind, adb)
          ->Unit(benchmark::kMicrosecond);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  registerAll();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
