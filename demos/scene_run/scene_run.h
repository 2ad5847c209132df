// The run of adb-demo: a scene (a file, or the pile made in code) built and stepped by
// adb::scene, with a progress bar, a line now and then, the outputs (steps.csv, events.jsonl,
// summary.json, frames and a movie), and the comparison of backends that `make demo` shows.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "adb/bullet/frame_budget.h"
#include "adb/scene/scene.h"

namespace adb::demo {

struct SceneRunOptions {
  std::string backend = "adb";  ///< adb, exact, gimpact or convex
  std::optional<int> steps;  ///< default: the scene's world.steps
  int every = 0;             ///< a line every N steps; 0: about ten lines
  std::filesystem::path out;  ///< empty: write nothing
  bool render = false;
  int width = 640, height = 480;
  int framesEvery = 0;  ///< a frame every N steps; 0: about 30 frames per simulated second
  int probeEvery = 0;   ///< penetration from the geometry every N steps (and the last)
  /// The steps strip.png shows; empty: an eighth of the run, its middle and its last step.
  std::vector<int> stripSteps;
  /// Run the scene with adb (its budget), exact contacts and GImpact, and compare.
  bool compare = false;
  /// Write contact_churn.csv and sleep_resets.csv (adb/scene/contact_trace.h) into `out`.
  bool contactTrace = false;
  // Overrides of the scene's world settings.
  std::optional<double> budgetMicros;
  std::optional<std::uint64_t> budgetNodePairs;
  std::optional<double> pMin, pAccept;
  std::optional<int> kMin;
  bool noSoften = false;
  std::optional<adb::FrameSettings::Fronts> fronts;
  std::optional<int> threads;
  bool noKeepContacts = false;  ///< resting pairs collide every step (an ablation)
  bool auditContacts = false;   ///< audit plausible contacts (FrameSettings::auditContacts)
};

/// Runs the scene; the exit code: 0, 1 when a body was lost (out of world.bounds) at some
/// step, or 2 when the scene's meshes are bad (one clear error on stderr) or an output cannot
/// be written.
int runScene(scene::Scene scene, const SceneRunOptions& options);

}  // namespace adb::demo
