// The command line of adb-tradeoff: what to measure (models, distances, rotations, methods,
// ADB parameter sweeps), where to write it, and the strict parsing of every value (numbers,
// lists, ranges a:b:step) with one clear error naming the flag and the value. CLI11 reads
// the flags (shared/command_line.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "adb/core/query.h"
#include "shared/command_line.h"

namespace adb::tradeoff {

/// A usage error: a bad flag or value. main() prints it and exits 2.
using UsageError = tools::UsageError;

/// One model: a mesh file or a generated model.
struct ModelSource {
  enum class Kind {
    File,       ///< a mesh file (--mesh, --against-mesh)
    Generated,  ///< adb::gen::makeModel(name, targetTriangles)
    Fixed,      ///< adb::gen::makeFixedModel(name): one resolution, no target
  };
  Kind kind = Kind::Generated;
  std::string path;                ///< File: the mesh file
  std::string name;                ///< Generated, Fixed: the model's name
  std::size_t targetTriangles = 0; ///< Generated: the requested triangle count
};

/// One case of the study, in command-line order: every query tests model `a` against model
/// `b` (--against-mesh, --against-model after a's --mesh or --model), or against a second
/// copy of `a` when `b` is empty (Zachmann's benchmark).
struct StudyCase {
  ModelSource a;
  std::optional<ModelSource> b;
};

/// Where the second body goes (--poses).
enum class PoseMode {
  /// Zachmann's benchmark: both bodies randomly rotated about their box centres, the centres
  /// each of --distances apart (in the pair's benchmark unit) along x.
  Distances,
  /// FCL's "robot in a room": a at the identity, b randomly rotated with its box centre
  /// uniformly random in a's bounding box.
  Inside,
};

struct Options {
  std::vector<StudyCase> cases;
  PoseMode poses = PoseMode::Distances;
  std::vector<double> distances;   ///< benchmark units (adb::benchmarkUnit), ascending
  bool distancesGiven = false;     ///< --distances was on the command line
  /// Random orientation pairs per distance; with --poses inside, the poses in all.
  int rotations = 200;
  std::uint64_t seed = 1;
  std::vector<std::string> methods{"adb", "exact", "gimpact", "fcl"};
  std::vector<double> pMins{0.5, 0.9, 0.99};
  std::vector<int> kMins{1, 5, 10};
  std::vector<double> budgetsUs;   ///< microseconds; +infinity is "none"
  std::vector<std::uint64_t> budgetPairs;  ///< ADB work budgets (node pairs); empty: none
  bool exactCounting = false;      ///< trees count possible collision cells exactly (paper 3.4)
  AdbKey adbKey = QuerySettings{}.adbKey;  ///< the ADB queue's key (--adb-key)
  std::string outDir = "tradeoff-results";
  bool plots = true;
  int repeats = 3;                 ///< timed runs per query (after one untimed warm-up)
  /// One untimed run of each query before its timed ones (--no-warmup: none, so that each
  /// query is timed cold, as a batch of different poses meets it).
  bool warmup = true;
  bool help = false;
  std::string commandLine;         ///< as given, for the summary
};

/// The generated-model triangle counts --model and --against-model accept.
inline constexpr std::size_t kMinModelTriangles = 1000;
inline constexpr std::size_t kMaxModelTriangles = 1000000;
inline constexpr std::size_t kDefaultModelTriangles = 20000;

/// Parses argv. Throws UsageError naming the flag and the offending value; with --help (or
/// -h) returns at once with `help` set.
Options parseOptions(int argc, const char* const* argv);

/// The --help text: every flag with its description and default, the timing and
/// calibration policy, the exit status.
std::string usageText();

/// Short file name without directory and extension ("meshes/bunny.ply" -> "bunny").
std::string fileStem(const std::string& path);

/// What a model is called in the output files: the file's stem or the model's name.
std::string sourceLabel(const ModelSource& source);

}  // namespace adb::tradeoff
