// adb-demo: runs scenes headless.
//
//   build/bin/adb-demo --scene FILE [options]
//   build/bin/adb-demo [--mesh FILE]... | [--model NAME] [--bodies N] [--triangles N]
//                      [--floor mesh|box|plane] [--seed S] [--no-sleep] [options]
//   options: [--steps N] [--out DIR] [--render] [--compare] [--backend adb|exact|gimpact|convex]
//            [--budget-us US | --budget-pairs N] [--probe-every N] ...
//
// With --scene, a scene file (docs/scenes.md); without it, the pile: generated bodies or
// copies of mesh files dropped into a bin (adb::scene::makePileScene). Either way the scene is
// built with only the effects it asks for and stepped by adb::scene; --out writes steps.csv,
// events.jsonl and summary.json, --render frames and a movie, --compare runs it with adb,
// exact contacts and GImpact side by side (make demo).
#include <CLI/CLI.hpp>

#include <cstdio>
#include <optional>

#include "adb/scene/pile_scene.h"
#include "adb/scene/scene_file.h"
#include "adb/support/mesh_generators.h"
#include "shared/command_line.h"
#include "scene_run/scene_run.h"

namespace {

struct Options {
  std::filesystem::path sceneFile;
  adb::demo::SceneRunOptions run;
  adb::scene::PileSpec pile;
  std::vector<std::filesystem::path> meshes;
  std::string floor = "mesh";
  bool noSleep = false;
  std::string fronts;
  int threads = 1;
  int steps = 0;
  double budgetMicros = 0;
  std::uint64_t budgetPairs = 0;
  double pMin = 0, pAccept = 0;
  int kMin = 0;
};

const char* const kPileOnly[] = {"--mesh",  "--model", "--bodies", "--triangles",
                                 "--seed", "--floor", "--no-sleep"};

void addOptions(CLI::App& app, Options& o) {
  app.add_option("--scene", o.sceneFile, "a scene file (docs/scenes.md); without it, the pile")
      ->check(CLI::ExistingFile);
  app.add_option("--backend", o.run.backend,
                 "adb (MeshShape under the budget; default), exact (MeshShape, no budget), "
                 "gimpact (Bullet's GImpact), convex (Bullet's HACD hulls)")
      ->check(CLI::IsMember({"adb", "exact", "gimpact", "convex"}));
  app.add_option("--steps", o.steps, "steps to run (default: the scene's world.steps; the "
                                     "pile's 300)")
      ->check(CLI::Range(1, 100000000));
  app.add_option("--every", o.run.every, "print a line every N steps (default: ten lines)")
      ->check(CLI::PositiveNumber);
  app.add_option("--out", o.run.out, "folder for steps.csv, events.jsonl, summary.json, "
                                     "frames/ and movie.mp4");
  app.add_option("--probe-every", o.run.probeEvery,
                 "measure body-body penetration from the geometry every N steps (untimed; the "
                 "same measure for every backend; 0: off)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--budget-us", o.budgetMicros,
                 "wall-clock budget per step for every pair with an adb mesh (overrides a "
                 "scene's)")
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
  app.add_flag("--no-soften", o.run.noSoften, "plausible contacts push as hard as exact ones");
  app.add_flag("--no-keep-contacts", o.run.noKeepContacts,
               "pairs at rest collide every step instead of keeping their contacts (to "
               "measure what keeping them does)");
  app.add_flag("--audit-contacts", o.run.auditContacts,
               "audit each step's plausible contacts against the triangles (untimed; the "
               "simulation is the same): steps.csv's audit_* columns, summary.json's audit");
  app.add_option("--fronts", o.fronts,
                 "mesh-mesh pairs keep the node pairs they evaluated and re-test what moved: "
                 "with a node-pair budget (default), always, or never")
      ->check(CLI::IsMember(std::vector<std::string>(adb::kFrontsNames.begin(),
                                                     adb::kFrontsNames.end())));

  app.add_option("--threads", o.threads,
                 "threads for adb's pair queries: 0 all hardware threads, 1 none (default); "
                 "the simulation is the same at any count")
      ->check(CLI::Range(0, adb::kMaxThreads));

  app.add_flag("--render", o.run.render, "write DIR/frames/NNNNN.png, DIR/strip.png and "
                                         "DIR/movie.mp4 (with ffmpeg); needs --out");
  app.add_flag("--contact-trace", o.run.contactTrace,
               "write DIR/contact_churn.csv (each step's contact points kept, new, moved, "
               "turned, dropped) and DIR/sleep_resets.csv (bodies whose deactivation timer "
               "reset, with their contacts' churn); needs --out");
  app.add_flag("--compare", o.run.compare,
               "run it with adb, exact and gimpact and compare (DIR/comparison.png with "
               "--render)");
  app.add_option("--strip-steps", o.run.stripSteps,
                 "the steps DIR/strip.png shows side by side (default: an eighth of the run, "
                 "its middle, its last step)")
      ->check(CLI::PositiveNumber)
      ->delimiter(',');
  app.add_option("--width", o.run.width, "frame width in pixels")->check(CLI::Range(16, 8192));
  app.add_option("--height", o.run.height, "frame height in pixels")->check(CLI::Range(16, 8192));
  app.add_option("--frames-every", o.run.framesEvery,
                 "a frame every N steps (default: about 30 per simulated second)")
      ->check(CLI::PositiveNumber);

  app.add_option("--mesh", o.meshes, "pile: bodies are copies of this mesh file (any format "
                                     "assimp reads), scaled to 0.8 across; repeat to cycle")
      ->check(CLI::ExistingFile);
  std::vector<std::string> models = adb::gen::modelNames();
  for (const std::string& name : adb::gen::realMeshModelNames()) models.push_back(name);
  app.add_option("--model", o.pile.model, "pile: every body this generated model (pipes, "
                                         "gears, knot, torus, sphere, lock; slivers: a CAD-like "
                                         "cylinder of 100:1 triangles; robot: a 296-triangle "
                                         "arm, room: a low-poly room) at --triangles (room and "
                                         "robot have one resolution), 0.8 across")
      ->check(CLI::IsMember(models))
      ->excludes("--mesh");
  app.add_flag("--no-sleep", o.noSleep, "pile: Bullet's deactivation off (bodies never sleep)");
  app.add_option("--bodies", o.pile.bodies, "pile: bodies (24)")->check(CLI::PositiveNumber);
  app.add_option("--triangles", o.pile.trianglesPerBody,
                 "pile: about this many triangles per generated body (1500)");
  app.add_option("--seed", o.pile.seed, "pile: random seed of the bodies' poses");
  app.add_option("--floor", o.floor, "pile: the bin: box meshes (default), btBoxShape floor and "
                                     "walls, or a btStaticPlaneShape floor between box walls")
      ->check(CLI::IsMember({"mesh", "box", "plane"}));
}

// The command line's overrides of the scene's world settings.
void takeOverrides(const CLI::App& app, Options& o) {
  adb::demo::SceneRunOptions& r = o.run;
  if (app.count("--steps")) r.steps = o.steps;
  if (app.count("--budget-us")) r.budgetMicros = o.budgetMicros;
  if (app.count("--budget-pairs")) r.budgetNodePairs = o.budgetPairs;
  if (app.count("--p-min")) r.pMin = o.pMin;
  if (app.count("--k-min")) r.kMin = o.kMin;
  if (app.count("--p-accept")) r.pAccept = o.pAccept;
  if (app.count("--fronts")) r.fronts = *adb::frontsNamed(o.fronts);  // checked by the parser
  if (app.count("--threads")) r.threads = o.threads;
}

adb::scene::Scene pileScene(Options& o) {
  using Floor = adb::scene::PileSpec::Floor;
  o.pile.floor = o.floor == "box" ? Floor::Box : o.floor == "plane" ? Floor::Plane : Floor::Mesh;
  o.pile.meshes = o.meshes;
  o.pile.sleeping = !o.noSleep;
  return adb::scene::makePileScene(o.pile);
}

int run(const CLI::App& app, Options& o) {
  if (!o.sceneFile.empty()) {
    for (const char* pileOnly : kPileOnly) {
      if (app.count(pileOnly)) {
        std::fprintf(stderr, "adb-demo: %s is for the pile, not with --scene\n", pileOnly);
        return 2;
      }
    }
  }
  if ((o.run.render || o.run.contactTrace) && o.run.out.empty()) {
    std::fprintf(stderr, "adb-demo: %s needs --out DIR\n",
                 o.run.render ? "--render" : "--contact-trace");
    return 2;
  }
  takeOverrides(app, o);
  adb::scene::Scene scene;
  try {
    scene = o.sceneFile.empty() ? pileScene(o) : adb::scene::loadScene(o.sceneFile);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "adb-demo: %s\n", e.what());
    return 2;
  }
  return adb::demo::runScene(std::move(scene), o.run);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"adb-demo: scenes headless (--scene FILE), or a pile of generated bodies or mesh "
               "files in a bin", "adb-demo"};
  Options o;
  addOptions(app, o);
  if (const std::optional<int> exitCode =
          adb::tools::parseCommandLine(app, "adb-demo", argc, argv)) {
    return *exitCode;
  }
  return run(app, o);
}
