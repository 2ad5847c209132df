#include "scene_run/scene_run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "adb/scene/contact_trace.h"
#include "adb/scene/recorder.h"
#include "adb/scene/scene_file.h"
#include "adb/scene/scene_world.h"
#include "shared/progress.h"
#include "render/png_file.h"
#include "scene_run/convex_peer.h"
#include "scene_run/movie.h"
#include "render/scene_picture.h"

namespace adb::demo {
namespace {

using scene::Backend;
using scene::RunSummary;
using scene::Scene;
using scene::SceneWorld;

struct RunResult {
  RunSummary summary;
  render::Image lastFrame{1, 1};
  std::vector<render::Image> strip;  // early, middle and last frames
  std::filesystem::path folder;
  bool rendered = false;
};

void applyOverrides(const SceneRunOptions& o, Scene& s) {
  if (o.steps) s.world.steps = *o.steps;
  if (o.budgetMicros) s.world.budget = {scene::BudgetSpec::Kind::Micros, *o.budgetMicros, 0};
  if (o.budgetNodePairs) {
    s.world.budget = {scene::BudgetSpec::Kind::NodePairs, 0.0, *o.budgetNodePairs};
  }
  if (o.pMin) s.world.pMin = *o.pMin;
  if (o.kMin) s.world.kMin = *o.kMin;
  if (o.pAccept) s.world.pAccept = *o.pAccept;
  if (o.noSoften) s.effects.softContacts = false;
  if (o.fronts) s.world.fronts = *o.fronts;
  if (o.threads) s.world.threads = *o.threads;
  if (o.noKeepContacts) s.world.keepRestingContacts = false;
  if (o.auditContacts) s.world.auditContacts = true;
}

std::string budgetText(const scene::BudgetSpec& b) {
  char text[64];
  switch (b.kind) {
    case scene::BudgetSpec::Kind::Micros:
      std::snprintf(text, sizeof text, "%.0f us per step", b.micros);
      return text;
    case scene::BudgetSpec::Kind::NodePairs:
      std::snprintf(text, sizeof text, "%llu node pairs per step",
                    static_cast<unsigned long long>(b.nodePairs));
      return text;
    default:
      return "none";
  }
}

// About 30 frames per simulated second, or every step of a slower scene.
int framesEvery(const SceneRunOptions& o, const Scene& s) {
  if (o.framesEvery > 0) return o.framesEvery;
  return std::max(1, static_cast<int>(std::lround(1.0 / (30.0 * s.world.timeStep))));
}

// The steps of the strip's frames: as asked, or an eighth of the run, its middle and its end.
std::vector<int> stripSteps(const SceneRunOptions& o, int steps) {
  if (!o.stripSteps.empty()) return o.stripSteps;
  return {std::max(1, steps / 8), std::max(1, steps / 2), steps};
}

void printLine(const scene::StepRecord& r, const scene::Effects& effects) {
  if (effects.kind == scene::Effects::Kind::Overlap) {
    std::printf("%6d %9.3f %6u %5u %9.4f %11u %7u\n", r.step, 1e3 * r.seconds, r.meshPairs,
                r.cutPairs, r.meanConfidence, r.overlapping, r.events);
  } else {
    std::printf("%6d %9.3f %6u %5u %9.4f %8u %10.4f %10.3f %7d %6d %4d\n", r.step,
                1e3 * r.seconds, r.meshPairs, r.cutPairs, r.meanConfidence, r.contacts,
                r.penetration, r.energy, r.atRest, r.asleep, r.lost);
  }
}

void printHeader(const scene::Effects& effects) {
  if (effects.kind == scene::Effects::Kind::Overlap) {
    std::printf("%6s %9s %6s %5s %9s %11s %7s\n", "step", "ms/step", "pairs", "cut", "conf.",
                "overlapping", "events");
  } else {
    std::printf("%6s %9s %6s %5s %9s %8s %10s %10s %7s %6s %4s\n", "step", "ms/step", "pairs",
                "cut", "conf.", "contacts", "max pen.", "energy", "at rest", "asleep", "lost");
  }
}

RunResult runOne(const Scene& scene, Backend backend, const SceneRunOptions& o,
                 const std::filesystem::path& folder) {
  RunResult result;
  result.folder = folder;
  DecompositionReport decomposition;
  SceneWorld world(scene, backend, convexShapeMaker(decomposition));
  const scene::BuildReport& built = world.built();
  if (backend == Backend::Convex) {
    std::printf("convex decomposition (HACD): %s\n", decomposition.describe().c_str());
  }
  std::printf("scene %s: %s\n  backend %s, %d bodies (%d meshes, %zu triangles), built in "
              "%.2f s\n  world: %s\n  budget %s, p_min %.3g, k_min %d, p_accept %.3g\n",
              scene.file.empty() ? "(made in code)" : scene.file.filename().string().c_str(),
              scene.description.c_str(),
              toString(backend), built.bodies, built.meshBodies, built.triangles,
              built.buildSeconds, built.describe().c_str(),
              backend == Backend::Adb ? budgetText(scene.world.budget).c_str() : "none",
              scene.world.pMin, scene.world.kMin, scene.world.pAccept);
  std::unique_ptr<scene::Recorder> recorder =
      folder.empty() ? std::make_unique<scene::Recorder>(world)
                     : std::make_unique<scene::Recorder>(world, folder);
  std::unique_ptr<scene::ContactTrace> trace;
  if (o.contactTrace) trace = std::make_unique<scene::ContactTrace>(folder);
  const int steps = scene.world.steps;
  const int every = o.every > 0 ? o.every : std::max(1, steps / 10);
  const int frameEvery = framesEvery(o, scene);
  const render::Camera camera = sceneCamera(world);
  const std::vector<int> strip = stripSteps(o, steps);
  if (o.render) std::filesystem::create_directories(folder / "frames");
  printHeader(scene.effects);
  tools::Progress progress(static_cast<std::uint64_t>(steps), "steps");
  int frame = 0;
  for (int step = 1; step <= steps; ++step) {
    const scene::StepRecord& r = world.step();
    const bool probe = o.probeEvery > 0 && (step % o.probeEvery == 0 || step == steps);
    if (probe) {
      const scene::PenetrationReport probed = world.probePenetration();
      recorder->record(world, &probed);
    } else {
      recorder->record(world);
    }
    if (trace) trace->record(world);
    const bool inStrip = std::find(strip.begin(), strip.end(), step) != strip.end();
    const bool inMovie = step % frameEvery == 0 || step == steps;
    if (o.render && (inStrip || inMovie)) {
      result.lastFrame = drawScene(world, camera, o.width, o.height,
                                   sceneCaption(world, recorder->meanStepMillisSoFar()));
      if (inStrip) result.strip.push_back(result.lastFrame);
      result.rendered = true;
    }
    if (o.render && inMovie) {
      char name[32];
      std::snprintf(name, sizeof name, "%05d.png", frame++);
      render::writePng(result.lastFrame, folder / "frames" / name);
    }
    if (step % every == 0 || step == steps) {
      progress.hide();
      printLine(r, scene.effects);
      std::fflush(stdout);
    }
    progress.advance();
  }
  progress.finish();
  result.summary = recorder->finish();
  if (trace) {
    const scene::ContactChurn& c = trace->total();
    std::printf("contacts over the run: %u points held, %.1f %% with last step's features, "
                "%.1f %% matched, %u new, %u moved over 1 mm, %u turned over 1 degree, %u "
                "dropped; deactivation timers reset %llu times (%s/contact_churn.csv, "
                "sleep_resets.csv)\n",
                c.points, c.points ? 100.0 * c.keptId / c.points : 0.0,
                c.points ? 100.0 * c.matched / c.points : 0.0, c.fresh, c.moved, c.turned,
                c.dropped, static_cast<unsigned long long>(trace->resets()),
                folder.string().c_str());
  }
  if (o.render) {
    const int fps = std::max(1, static_cast<int>(std::lround(1.0 / (frameEvery * scene.world.timeStep))));
    const std::string movie = writeMovie(folder / "frames", fps, folder / "movie.mp4");
    if (!result.strip.empty()) render::writePng(render::sideBySide(result.strip), folder / "strip.png");
    std::printf("frames: %s/frames/ (%d), strip of three: %s/strip.png%s%s\n",
                folder.string().c_str(), frame, folder.string().c_str(),
                movie.empty() ? "" : "; movie: ", movie.c_str());
  }
  return result;
}

void printSummary(const RunSummary& s) {
  std::printf("\n%d steps: %.3f ms/step mean, %.3f p99, %.3f max; adb's pairs %.3f ms/step mean, "
              "%.3f p99; contacts exact %llu, plausible %llu\n",
              s.steps, s.meanStepMillis, s.p99StepMillis, s.maxStepMillis, s.meanPairMillis,
              s.p99PairMillis, static_cast<unsigned long long>(s.exactContacts),
              static_cast<unsigned long long>(s.plausibleContacts));
  std::printf("budget use %.2f; pairs cut %llu of %llu; confidence mean %.4f, worst %.4f\n",
              s.meanBudgetUse,
              static_cast<unsigned long long>(s.cutPairSteps),
              static_cast<unsigned long long>(s.meshPairSteps), s.meanConfidence,
              s.worstConfidence);
  if (s.effects.rfind("overlap", 0) == 0) {
    std::printf("overlap events: %llu\n", static_cast<unsigned long long>(s.events));
  } else {
    std::printf("deepest contact %.4f (mean of each step's %.4f)", s.maxPenetration,
                s.meanPenetration);
    if (s.maxProbedPenetration >= 0) {
      std::printf(", body-body penetration from the geometry %.4f (each body's deepest, "
                  "averaged over bodies and probes, %.4f)",
                  s.maxProbedPenetration, s.meanProbedPenetration);
    }
    std::printf("\n");
  }
  if (s.dynamicBodies == 0) return;
  std::printf("at rest at the end: %d of %d; asleep (Bullet's deactivation) %d", s.atRestAtEnd,
              s.dynamicBodies, s.asleepAtEnd);
  if (s.allAsleepFrom > 0) std::printf(", all from step %d", s.allAsleepFrom);
  std::printf("; kinetic energy %.4f J\n", s.kineticAtEnd);
  if (!s.worldBounds) {
    std::printf("bodies lost (fallen below the lowest static body): %d at most, %d at the end\n",
                s.mostLost, s.lostAtEnd);
    return;
  }
  std::printf("bodies lost (out of the world's bounds): %d at most, %d at the end; deepest "
              "vertex out of the bounds %.4f (%.2f %% of its body's size), at the end %.4f\n",
              s.mostLost, s.lostAtEnd, s.maxOutOfBounds, 100 * s.maxOutOfBoundsRelative,
              s.outOfBoundsAtEnd);
}

void printComparison(const std::vector<RunResult>& runs) {
  const double gimpact = runs.back().summary.meanStepMillis;
  std::printf("\n| backend | ms/step | max ms/step | vs GImpact | pairs cut | mean conf. | "
              "worst conf. | deepest contact | probed penetration | at rest (end) | asleep (end) "
              "| all asleep from | lost | kinetic energy (end) |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const RunResult& r : runs) {
    const RunSummary& s = r.summary;
    const std::string asleepFrom =
        s.allAsleepFrom > 0 ? "step " + std::to_string(s.allAsleepFrom) : std::string("never");
    std::printf("| %s | %.2f | %.2f | %.1fx | %llu/%llu | %.4f | %.4f | %.4f | %.4f | %d/%d | "
                "%d/%d | %s | %d | %.3f J |\n",
                s.backend.c_str(), s.meanStepMillis, s.maxStepMillis,
                s.meanStepMillis > 0 ? gimpact / s.meanStepMillis : 0.0,
                static_cast<unsigned long long>(s.cutPairSteps),
                static_cast<unsigned long long>(s.meshPairSteps), s.meanConfidence,
                s.worstConfidence, s.maxPenetration, s.maxProbedPenetration, s.atRestAtEnd,
                s.dynamicBodies, s.asleepAtEnd, s.dynamicBodies, asleepFrom.c_str(), s.mostLost,
                s.kineticAtEnd);
  }
}

int compare(const Scene& scene, const SceneRunOptions& o) {
  std::vector<RunResult> runs;
  std::vector<render::Image> frames;
  for (Backend b : {Backend::Adb, Backend::Exact, Backend::GImpact}) {
    std::printf("\n== %s ==\n", toString(b));
    runs.push_back(runOne(scene, b, o, o.out.empty() ? o.out : o.out / toString(b)));
    printSummary(runs.back().summary);
    if (runs.back().rendered) frames.push_back(runs.back().lastFrame);
  }
  printComparison(runs);
  if (frames.size() == runs.size() && !o.out.empty()) {
    const std::filesystem::path picture = o.out / "comparison.png";
    render::writePng(render::sideBySide(frames), picture);
    std::printf("\npicture (last frame of each run, adb | exact | GImpact): %s\n",
                picture.string().c_str());
  }
  return runs.front().summary.mostLost > 0 ? 1 : 0;
}

}  // namespace

int runScene(Scene scene, const SceneRunOptions& o) {
  try {
    applyOverrides(o, scene);
    if (o.compare) return compare(scene, o);
    const RunResult r = runOne(scene, scene::parseBackend(o.backend), o, o.out);
    printSummary(r.summary);
    if (!o.out.empty()) std::printf("outputs: %s\n", o.out.string().c_str());
    return r.summary.mostLost > 0 ? 1 : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "adb-demo: %s\n", e.what());
    return 2;
  }
}

}  // namespace adb::demo
