// adb-demo: runs scenes headless.
//
//   build/bin/adb-demo --scene FILE [--steps N] [--out DIR] [--render] [--backend adb|exact|gimpact]
//                      [--compare] [--budget-us US | --budget-pairs N] ...
//   build/bin/adb-demo [--mesh FILE]... [--bodies N] [--triangles N] [--floor mesh|box|plane]
//                      [--backend adb|gimpact|convex] ...
//
// With --scene, a scene file (docs/scenes.md) is built with only the effects it asks for and
// stepped (adb::scene); --out writes steps.csv, events.jsonl and summary.json, --render frames
// and a movie, --compare runs it with adb, exact contacts and GImpact side by side (make demo).
// Without it, the pile: generated bodies or copies of mesh files dropped into a bin, with the
// figures the budget sweep reads.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <optional>

#include "adb/io/mesh_file.h"
#include "common/command_line.h"
#include "pile/pile_run.h"
#include "scene_run/scene_run.h"

namespace {

struct Options {
  adb::demo::SceneRunOptions scene;
  adb::demo::PileRunOptions pile;
  std::vector<std::string> meshes;
  std::string floor = "mesh";
  std::string fronts;
  double budgetMicros = 0;
  std::uint64_t budgetPairs = 0;
  double pMin = 0, pAccept = 0;
  int kMin = 0;
};

// --fronts' values (checked by the parser) as FrameSettings::Fronts.
adb::FrameSettings::Fronts frontsOf(const std::string& name) {
  using Fronts = adb::FrameSettings::Fronts;
  return name == "always" ? Fronts::Always : name == "never" ? Fronts::Never
                                                             : Fronts::WithNodePairBudget;
}

void addOptions(CLI::App& app, Options& o) {
  app.add_option("--scene", o.scene.scene, "a scene file (docs/scenes.md); without it, the pile")
      ->check(CLI::ExistingFile);
  app.add_option("--backend", o.scene.backend,
                 "adb (MeshShape under the budget; default), exact (MeshShape, no budget), "
                 "gimpact (Bullet's GImpact); the pile also takes convex (Bullet's HACD hulls)")
      ->check(CLI::IsMember({"adb", "exact", "gimpact", "convex"}));
  app.add_option("--steps", o.pile.steps, "steps to run (a scene's default: its world.steps)")
      ->check(CLI::Range(1, 100000000));
  app.add_option("--every", o.pile.every, "print a line every N steps")->check(CLI::PositiveNumber);
  app.add_option("--out", o.pile.out, "folder for steps.csv (and a scene's events.jsonl, "
                                      "summary.json, frames/, movie.mp4)");
  app.add_option("--probe-every", o.pile.probeEvery,
                 "measure body-body penetration from the geometry every N steps (untimed; the "
                 "same measure for every backend; 0: off)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--budget-us", o.budgetMicros,
                 "wall-clock budget per step for every pair with an adb mesh (default none; "
                 "overrides a scene's)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--budget-pairs", o.budgetPairs,
                 "node pairs per step for every pair with an adb mesh: reproducible");
  app.add_option("--p-min", o.pMin, "quality target: probability above which a node pair counts")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--k-min", o.kMin,
                 "stop refining a pair at k_min node pairs above p_min (0: never)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--p-accept", o.pAccept,
                 "unresolved node pairs at or above it become plausible contacts (0.9)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_flag("--no-soften", o.scene.noSoften, "plausible contacts push as hard as exact ones");
  app.add_option("--fronts", o.fronts,
                 "mesh-mesh pairs keep the node pairs they evaluated and re-test what moved: "
                 "with a node-pair budget (default), always, or never")
      ->check(CLI::IsMember({"node_pair_budget", "always", "never"}));

  app.add_flag("--render", o.scene.render, "scene: write DIR/frames/NNNNN.png and DIR/movie.mp4 "
                                           "(with ffmpeg); needs --out");
  app.add_flag("--compare", o.scene.compare,
               "scene: run it with adb, exact and gimpact and compare (DIR/comparison.png "
               "with --render)");
  app.add_option("--strip-steps", o.scene.stripSteps,
                 "scene: the steps DIR/strip.png shows side by side (default: an eighth of the "
                 "run, its middle, its last step)")
      ->check(CLI::PositiveNumber)
      ->delimiter(',');
  app.add_option("--width", o.scene.width, "frame width in pixels")->check(CLI::Range(16, 8192));
  app.add_option("--height", o.scene.height, "frame height in pixels")->check(CLI::Range(16, 8192));
  app.add_option("--frames-every", o.scene.framesEvery,
                 "a frame every N steps (default: about 30 per simulated second)")
      ->check(CLI::PositiveNumber);

  app.add_option("--mesh", o.meshes, "pile: bodies are copies of this mesh file (any format "
                                     "assimp reads), scaled to 0.8 across; repeat to cycle")
      ->check(CLI::ExistingFile);
  app.add_option("--bodies", o.pile.settings.bodies, "pile: bodies (24)")->check(CLI::PositiveNumber);
  app.add_option("--triangles", o.pile.settings.trianglesPerBody,
                 "pile: about this many triangles per generated body (1500)");
  app.add_option("--seed", o.pile.settings.seed, "pile: random seed of the bodies' poses");
  app.add_option("--floor", o.floor, "pile: the bin: box meshes (default), btBoxShape floor and "
                                     "walls, or a btStaticPlaneShape floor between box walls")
      ->check(CLI::IsMember({"mesh", "box", "plane"}));
}

int runPile(const CLI::App& app, Options& o) {
  using adb::demo::Backend;
  adb::demo::PileRunOptions& p = o.pile;
  if (o.scene.backend == "exact") {
    std::fprintf(stderr, "adb-demo: --backend exact is for scenes; the pile's adb backend "
                         "without a budget is exact\n");
    return 2;
  }
  if (o.scene.render || o.scene.compare) {
    std::fprintf(stderr, "adb-demo: --render and --compare need --scene\n");
    return 2;
  }
  p.settings.backend = o.scene.backend == "gimpact"  ? Backend::GImpact
                       : o.scene.backend == "convex" ? Backend::Convex
                                                     : Backend::Adb;
  p.settings.floor = o.floor == "box"     ? adb::demo::Floor::Box
                     : o.floor == "plane" ? adb::demo::Floor::Plane
                                          : adb::demo::Floor::Mesh;
  adb::FrameSettings& f = p.settings.frame;
  if (app.count("--budget-us")) f.budgetMicros = o.budgetMicros;
  if (app.count("--budget-pairs")) f.budgetNodePairs = o.budgetPairs;
  if (app.count("--p-min")) f.pMin = o.pMin;
  if (app.count("--k-min")) f.kMin = o.kMin;
  if (app.count("--p-accept")) f.pAccept = o.pAccept;
  f.softenPlausible = !o.scene.noSoften;
  if (app.count("--fronts")) f.fronts = frontsOf(o.fronts);
  try {
    for (const std::string& file : o.meshes) p.settings.meshes.push_back(adb::io::loadMesh(file));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "adb-demo: %s\n", e.what());
    return 2;
  }
  return adb::demo::runPile(p);
}

int runScene(const CLI::App& app, Options& o) {
  adb::demo::SceneRunOptions& s = o.scene;
  if (o.scene.backend == "convex") {
    std::fprintf(stderr, "adb-demo: --backend convex is for the pile, not scenes\n");
    return 2;
  }
  for (const char* pileOnly : {"--mesh", "--bodies", "--triangles", "--seed", "--floor"}) {
    if (app.count(pileOnly)) {
      std::fprintf(stderr, "adb-demo: %s is for the pile, not with --scene\n", pileOnly);
      return 2;
    }
  }
  if (s.render && o.pile.out.empty()) {
    std::fprintf(stderr, "adb-demo: --render needs --out DIR\n");
    return 2;
  }
  if (app.count("--steps")) s.steps = o.pile.steps;
  if (app.count("--every")) s.every = o.pile.every;
  s.out = o.pile.out;
  s.probeEvery = o.pile.probeEvery;
  if (app.count("--budget-us")) s.budgetMicros = o.budgetMicros;
  if (app.count("--budget-pairs")) s.budgetNodePairs = o.budgetPairs;
  if (app.count("--p-min")) s.pMin = o.pMin;
  if (app.count("--k-min")) s.kMin = o.kMin;
  if (app.count("--p-accept")) s.pAccept = o.pAccept;
  if (app.count("--fronts")) s.fronts = frontsOf(o.fronts);
  return adb::demo::runScene(s);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"adb-demo: scenes headless (--scene FILE), or a pile of generated bodies or mesh "
               "files in a bin", "adb-demo"};
  Options o;
  addOptions(app, o);
  if (const std::optional<int> exitCode =
          adb::demo::parseCommandLine(app, "adb-demo", argc, argv)) {
    return *exitCode;
  }
  return o.scene.scene.empty() ? runPile(app, o) : runScene(app, o);
}
