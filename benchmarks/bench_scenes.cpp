// adb-bench-scenes: what each effect costs. The same geometry, the gallery's pile
// (demos/scenes/pile.json) after it has fallen and settled, is stepped as an overlap scene
// (boolean queries, no contacts, no solver), a contacts scene (contacts, no solver) and a
// dynamics scene (with friction), with adb's shapes (no budget: exact) and with GImpact. The
// runner builds only what a scene asks for, so an overlap scene must cost less than a contacts
// one, and that less than dynamics.
//
//   build/bin/adb-bench-scenes [--benchmark_min_time=1]
#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>

#include "adb/scene/scene_file.h"
#include "adb/scene/scene_world.h"

namespace {

using adb::scene::Backend;
using adb::scene::Effects;
using adb::scene::Scene;
using adb::scene::SceneWorld;

// Steps of dynamics before the poses are taken: the pile has landed and mostly settled.
constexpr int kSettleSteps = 150;

// The pile as it lies after settling, every body at rest where it came to lie.
const Scene& settledPile() {
  static const Scene settled = [] {
    Scene pile = adb::scene::loadScene(ADB_SCENES_DIR "/pile.json");
    pile.world.budget = {};
    SceneWorld world(pile, Backend::Exact);
    for (int i = 0; i < kSettleSteps; ++i) world.step();
    for (std::size_t b = 0; b < world.bodyCount(); ++b) {
      pile.bodies[b].pose = world.scenePose(b);
      pile.bodies[b].velocity = adb::Vec3::Zero();
      pile.bodies[b].angularVelocity = adb::Vec3::Zero();
    }
    return pile;
  }();
  return settled;
}

Scene withEffects(Effects::Kind kind) {
  Scene s = settledPile();
  s.effects = Effects{};
  s.effects.kind = kind;
  s.effects.friction = kind == Effects::Kind::Dynamics;
  return s;
}

void stepScene(benchmark::State& state, Effects::Kind kind, Backend backend) {
  SceneWorld world(withEffects(kind), backend);
  world.step();  // the first step builds the broadphase and the manifolds
  std::uint64_t pairs = 0, contacts = 0;
  for (auto _ : state) {
    const adb::scene::StepRecord& r = world.step();
    pairs += r.meshPairs;
    contacts += r.contacts;
  }
  state.counters["contacts/step"] =
      benchmark::Counter(static_cast<double>(contacts), benchmark::Counter::kAvgIterations);
  state.counters["mesh_pairs/step"] =
      benchmark::Counter(static_cast<double>(pairs), benchmark::Counter::kAvgIterations);
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  const std::map<Effects::Kind, const char*> kinds = {{Effects::Kind::Overlap, "overlap"},
                                                      {Effects::Kind::Contacts, "contacts"},
                                                      {Effects::Kind::Dynamics, "dynamics"}};
  for (Backend backend : {Backend::Exact, Backend::GImpact}) {
    for (const auto& [kind, name] : kinds) {
      const std::string label = std::string("pile/") + name + "/" + adb::scene::toString(backend);
      benchmark::RegisterBenchmark(label.c_str(), stepScene, kind, backend)
          ->Unit(benchmark::kMillisecond);
    }
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
