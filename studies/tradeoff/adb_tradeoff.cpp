// adb-tradeoff: what accuracy costs in time. Runs Zachmann's benchmark (two copies of each
// model, or a model and another one, at a range of distances, seeded random orientations; or
// the second body anywhere in the first's bounding box, FCL's robot in a room) through the
// ADB-tree's ADB
// modes (sweeps of p_min, k_min and the time or work budget), its exact mode, Bullet's
// GImpact and FCL, and opt-in baselines without probability (exact mode cut by a budget, a
// box-first search, the root boxes alone), all on the same poses, and writes queries.csv
// (every query, poses at full precision), summary.csv / summary.md (per case, method and
// parameters; the budgets that reach 5 % and 1 % error), reliability.csv (calibration of
// the confidences), cells.csv (the paper's Fig. 8), distances.csv (Figs. 9 and 10, judged) and, through
// studies/tradeoff/plot_tradeoff.py, the plots. Format and procedure:
// docs/benchmark.md. Timing policy: timing.h (also in --help).
//
// Exit status: 0 done, 2 usage error (nothing run), 1 input error (a mesh that cannot be
// read or is invalid): cases are processed in command-line order and the files describe
// the cases finished before the error.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cell_histogram.h"
#include "methods.h"
#include "model_loader.h"
#include "options.h"
#include "plots.h"
#include "shared/progress.h"
#include "query_csv.h"
#include "report.h"
#include "study.h"

namespace {

using namespace adb::tradeoff;

constexpr int kInputError = 1;
constexpr int kUsageError = 2;

void printError(const std::string& message) {
  std::fprintf(stderr, "adb-tradeoff: error: %s\n", message.c_str());
}

// The cell histograms of a pair's two trees as one (cells.csv has one histogram per case):
// counts and node totals added, the coarser sampling stride kept.
adb::CellHistogram combined(const adb::CellHistogram& a, const adb::CellHistogram& b) {
  adb::CellHistogram sum = a;
  for (std::size_t c = 0; c < sum.count.size(); ++c) sum.count[c] += b.count[c];
  sum.nodesCounted += b.nodesCounted;
  sum.nodesTotal += b.nodesTotal;
  sum.stride = std::max(a.stride, b.stride);
  sum.seconds += b.seconds;
  return sum;
}

// Loads, measures and histograms one case (a model, or a model and the one it is tested
// against); appends it to `done` and rewrites the reports.
void studyCase(const Options& o, std::size_t index, StudyContext& context, SharedTree& tree,
               std::vector<ModelResult>& done) {
  std::vector<std::string> warnings;
  const StudyCase& c = o.cases[index];
  // Model keys: 2 x the case's position, + 1 for its second model (Model::index).
  const Model a = loadModel(c.a, 2 * index, warnings);
  std::optional<Model> b;
  if (c.b) b = loadModel(*c.b, 2 * index + 1, warnings);
  for (const std::string& w : warnings) context.progress.note("adb-tradeoff: warning: " + w);
  const Model& against = b ? *b : a;
  ModelResult result = runCase(a, against, index, context);
  result.cells = cellHistogram(tree.treeFor(a));
  if (b) result.cells = combined(result.cells, cellHistogram(tree.treeFor(*b)));
  done.push_back(std::move(result));
  writeReports(o, done);
}

// The trees' build settings: the defaults, with the cell counts --exact-counting asks for.
adb::BuildSettings treeSettings(const Options& o) {
  adb::BuildSettings s;
  s.counting = o.exactCounting ? adb::CellCounting::Exact : adb::CellCounting::Approximate;
  return s;
}

int run(const Options& o) {
  std::error_code ec;
  std::filesystem::create_directories(o.outDir, ec);
  if (ec) {
    printError("--out '" + o.outDir + "': cannot create the directory: " + ec.message());
    return kInputError;
  }
  auto tree = std::make_shared<SharedTree>(treeSettings(o));
  std::vector<std::unique_ptr<Method>> methods = makeMethods(o, tree);
  QueryCsv csv(o.outDir + "/queries.csv");
  adb::tools::Progress progress(queriesPerCase(o, methods.size()) * o.cases.size(), "queries");
  StudyContext context{o, methods, csv, progress};
  std::vector<ModelResult> done;
  writeReports(o, done);  // headers only: the files exist even if the first case fails
  for (std::size_t i = 0; i < o.cases.size(); ++i) {
    try {
      studyCase(o, i, context, *tree, done);
    } catch (const std::exception& e) {
      progress.finish();
      printError(e.what());
      std::fprintf(stderr, "adb-tradeoff: results of the %zu case(s) before it are in %s\n",
                   done.size(), o.outDir.c_str());
      return kInputError;
    }
  }
  progress.finish();
  std::fprintf(stderr, "adb-tradeoff: wrote %s/{queries.csv,summary.csv,summary.md,reliability.csv,"
               "cells.csv,distances.csv}\n",
               o.outDir.c_str());
  if (o.plots) runPlotScript(o.outDir);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options options;
  try {
    options = parseOptions(argc, argv);
  } catch (const UsageError& e) {
    printError(e.what());
    std::fprintf(stderr, "run 'adb-tradeoff --help' for the options\n");
    return kUsageError;
  }
  if (options.help) {
    std::fputs(usageText().c_str(), stdout);
    return 0;
  }
  try {
    return run(options);
  } catch (const std::exception& e) {  // output files that cannot be written, say
    printError(e.what());
    return kInputError;
  }
}
