// The pile run of adb-demo: generated concave bodies, or copies of mesh files, dropped into a
// bin (pile_scene.h) with adb, GImpact or a convex decomposition; a line every N steps, a
// final table, and the per-step figures as CSV (the budget sweep reads them).
#pragma once

#include <string>

#include "pile/pile_scene.h"

namespace adb::demo {

struct PileRunOptions {
  SceneSettings settings;
  int steps = 300;
  int every = 30;
  int probeEvery = 0;  ///< measure body-body penetration from the geometry every N steps
  std::string out;     ///< folder for steps.csv; empty: none
};

/// Runs the pile; the exit code: 0, 1 when a body fell through the floor, 2 when the scene
/// could not be built.
int runPile(const PileRunOptions& o);

}  // namespace adb::demo
