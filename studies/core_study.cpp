// adb-core-study: ADB (p_min, k_min) against the exact mode of the same tree, on the same
// benchmark poses, for the generated models: error rate (paper's measure: wrong answers among
// queries whose root boxes overlap), mean query time of each mode, node pairs, stop reasons.
// Prints a Markdown table (docs/core-results.md is made with it).
//
//   build/bin/adb-core-study [--triangles N[,N...]] [--poses N] [--p-min P] [--k-min K]
//                            [--models a,b,...] [--exact-counting] [--grid G]
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "adb/support/benchmark_poses.h"
#include "adb/support/mesh_generators.h"
#include "adb/core/query.h"
#include "adb/core/tree.h"
#include "shared/command_line.h"

namespace {

struct Options {
  std::vector<std::size_t> triangles{20000};
  std::vector<std::string> models{"knot", "pipes", "gears", "lock", "torus"};
  int poses = 30;
  double pMin = 0.99;
  int kMin = 10;
  adb::CellCounting counting = adb::CellCounting::Approximate;
  int grid = adb::BuildSettings{}.gridResolution;
};

// Comma-separated items; "a,,b" and a trailing comma give empty items, which the callers
// reject.
std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  if (s.empty() || s.back() == ',') out.emplace_back();
  return out;
}

std::string joined(const std::vector<std::string>& items, const char* separator = ",") {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : separator) + item;
  return out;
}

std::vector<std::size_t> parseTriangles(const std::string& text) {
  std::vector<std::size_t> out;
  for (const std::string& item : split(text)) {
    out.push_back(static_cast<std::size_t>(
        adb::tools::parseIntegerIn("--triangles", item, 1, std::numeric_limits<long long>::max())));
  }
  return out;
}

// Names checked here: makeModel would only fail after the models before it were measured.
std::vector<std::string> parseModels(const std::string& text) {
  const std::vector<std::string> known = adb::gen::modelNames();
  const std::vector<std::string> out = split(text);
  for (const std::string& name : out) {
    if (std::find(known.begin(), known.end(), name) == known.end()) {
      adb::tools::failValue("--models", name,
                           "unknown model; known models: " + joined(known, ", "));
    }
  }
  return out;
}

// The ranges are those adb::validate and AdbTree's constructor accept (kMin >= 1, pMin in
// [0, 1], grid 1..32): a bad value is a usage error rather than an exception mid-run.
void addOptions(CLI::App& app, Options& o) {
  app.description(
      "adb-core-study: ADB (p_min, k_min) against the exact mode of the same tree, on the same\n"
      "benchmark poses (distances 0.4..2.0 by 0.1, seed 1), for the generated models: error\n"
      "rate among queries whose root boxes overlap, mean query time (best of 3 runs), node\n"
      "pairs, stop reasons; a Markdown table (docs/core-results.md).");
  adb::tools::addValueOption(
      app, "--triangles", "N[,N...]", "about N triangles per model; each N is a row",
      [&o](const std::string& v) { o.triangles = parseTriangles(v); }, "20000");
  adb::tools::addValueOption(
      app, "--models", "LIST", "generated models (" + joined(adb::gen::modelNames(), ", ") + ")",
      [&o](const std::string& v) { o.models = parseModels(v); }, joined(o.models));
  adb::tools::addIntegerOption(app, "--poses", o.poses, 1, std::numeric_limits<int>::max(),
                              "random orientation pairs per distance");
  adb::tools::addValueOption(
      app, "--p-min", "P", "ADB's p_min, in [0, 1]",
      [&o](const std::string& v) {
        o.pMin = adb::tools::parseNumber("--p-min", v);
        if (o.pMin < 0.0 || o.pMin > 1.0) adb::tools::failValue("--p-min", v, "must be in [0, 1]");
      },
      "0.99");
  adb::tools::addIntegerOption(app, "--k-min", o.kMin, 1, 1000000, "ADB's k_min");
  app.add_flag_callback("--exact-counting", [&o] { o.counting = adb::CellCounting::Exact; },
                        "build the trees with exact cell counts (default approximate)")
      ->disable_flag_override();
  adb::tools::addIntegerOption(app, "--grid", o.grid, 1, 32, "cells per axis of each node's grid");
}

// The fastest of three runs: the machines are shared and noisy; the minimum is the query's.
adb::QueryResult timed(const adb::AdbTree& t, const adb::PosePair& p,
                       const adb::QuerySettings& s, adb::QueryScratch& scratch) {
  adb::QueryResult best = adb::collide(t, p.a, t, p.b, s, scratch);
  for (int i = 0; i < 2; ++i) {
    const adb::QueryResult r = adb::collide(t, p.a, t, p.b, s, scratch);
    if (r.seconds < best.seconds) best = r;
  }
  return best;
}

struct Row {
  int counted = 0, wrong = 0, quality = 0, exactHit = 0;
  int confident = 0, confidentWrong = 0;  // ADB answers with confidence >= 0.99
  double exactUs = 0, adbUs = 0, exactPairs = 0, adbPairs = 0;
};

Row measure(const adb::TriangleMesh& mesh, const adb::AdbTree& tree, const Options& o) {
  adb::QuerySettings exact;
  exact.mode = adb::QueryMode::Exact;
  adb::QuerySettings fast;
  fast.pMin = o.pMin;
  fast.kMin = o.kMin;
  adb::QueryScratch scratch;
  std::mt19937_64 rng(1);
  Row row;
  for (int step = 0; step <= 16; ++step) {
    for (int i = 0; i < o.poses; ++i) {
      const adb::PosePair p = adb::benchmarkPoses(mesh.bounds(), 0.4 + 0.1 * step, rng);
      const adb::QueryResult re = timed(tree, p, exact, scratch);
      const adb::QueryResult ra = timed(tree, p, fast, scratch);
      if (re.nodePairs <= 1 && !re.collides) continue;  // root boxes apart: not counted
      ++row.counted;
      row.wrong += re.collides != ra.collides ? 1 : 0;
      if (ra.confidence >= 0.99) {
        ++row.confident;
        row.confidentWrong += re.collides != ra.collides ? 1 : 0;
      }
      row.quality += ra.stop == adb::StopReason::QualityReached ? 1 : 0;
      row.exactHit += ra.stop == adb::StopReason::ExactHit ? 1 : 0;
      row.exactUs += re.seconds * 1e6;
      row.adbUs += ra.seconds * 1e6;
      row.exactPairs += static_cast<double>(re.nodePairs);
      row.adbPairs += static_cast<double>(ra.nodePairs);
    }
  }
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"", "adb-core-study"};
  Options o;
  addOptions(app, o);
  if (const std::optional<int> exitCode =
          adb::tools::parseCommandLine(app, "adb-core-study", argc, argv)) {
    return *exitCode;
  }
  std::printf("ADB p_min %.2f, k_min %d (%s cell counts, grid %d) vs exact mode, distances "
              "0.4..2.0, %d poses each, best of 3 runs per query\n\n",
              o.pMin, o.kMin, o.counting == adb::CellCounting::Exact ? "exact" : "approximate",
              o.grid, o.poses);
  std::printf("| model | triangles | counted | error %% | exact us | ADB us | speedup | "
              "exact pairs | ADB pairs | stop k_min %% | stop exact hit %% | wrong at conf >= 0.99 |\n");
  std::printf("|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const std::string& name : o.models) {
    for (std::size_t n : o.triangles) {
      const adb::TriangleMesh mesh = adb::gen::makeModel(name, n);
      adb::BuildSettings settings;
      settings.counting = o.counting;
      settings.gridResolution = o.grid;
      const adb::AdbTree tree(mesh, settings);
      const Row r = measure(mesh, tree, o);
      const double c = std::max(1, r.counted);
      std::printf("| %s | %zu | %d | %.2f | %.1f | %.1f | %.2f | %.0f | %.0f | %.0f | %.0f | %d of %d |\n",
                  name.c_str(), mesh.triangleCount(), r.counted, 100.0 * r.wrong / c,
                  r.exactUs / c, r.adbUs / c, r.adbUs > 0 ? r.exactUs / r.adbUs : 0.0,
                  r.exactPairs / c, r.adbPairs / c, 100.0 * r.quality / c,
                  100.0 * r.exactHit / c, r.confidentWrong, r.confident);
      std::fflush(stdout);
    }
  }
  return 0;
}
