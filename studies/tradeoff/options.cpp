// Parsing adb-tradeoff's command line: CLI11 reads the flags and builds --help from their
// descriptions; the list and range parsers here check every value completely (no atof-style
// "1.5abc" -> 1.5): a typo must not silently turn into another experiment.
#include "options.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "adb/support/mesh_generators.h"

namespace adb::tradeoff {
namespace {

// Ranges expand to at most this many distances: a step of 1e-9 is a typo, not a study.
constexpr std::size_t kMaxDistances = 10000;

using tools::failValue;
using tools::parseInteger;
using tools::parseIntegerIn;
using tools::parseNumber;

// The defaults of the list flags, parsed like the flags (and shown in --help as typed).
constexpr const char* kDefaultDistances = "0.4:2.0:0.1";
constexpr const char* kDefaultBudgets = "none,5,20,100";

std::vector<std::string> splitOn(const std::string& text, char sep) {
  std::vector<std::string> items;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, sep);) items.push_back(item);
  if (!text.empty() && text.back() == sep) items.emplace_back();  // "1,2," has an empty item
  return items;
}

// Rounds away the binary residue of a + i * step (0.30000000000000004 -> 0.3), so that
// distances print and group as typed.
double tidy(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.12g", v);
  return std::strtod(buf, nullptr);
}

// "a:b:step" (inclusive of b up to rounding) or a single number.
void appendRange(const std::string& flag, const std::string& item, std::vector<double>& out) {
  const std::vector<std::string> parts = splitOn(item, ':');
  if (parts.size() == 1) {
    out.push_back(tidy(parseNumber(flag, item)));
    return;
  }
  if (parts.size() != 3) failValue(flag, item, "expected a number or a range start:end:step");
  const double a = parseNumber(flag, parts[0]);
  const double b = parseNumber(flag, parts[1]);
  const double step = parseNumber(flag, parts[2]);
  if (!(step > 0.0)) failValue(flag, item, "the step must be positive");
  if (b < a) failValue(flag, item, "the end is below the start");
  const double count = std::floor((b - a) / step + 1e-9) + 1.0;
  if (count > static_cast<double>(kMaxDistances)) {
    failValue(flag, item, "more than " + std::to_string(kMaxDistances) + " values");
  }
  for (int i = 0; i < static_cast<int>(count); ++i) out.push_back(tidy(a + i * step));
}

std::vector<double> parseDistances(const std::string& flag, const std::string& text) {
  std::vector<double> out;
  for (const std::string& item : splitOn(text, ',')) appendRange(flag, item, out);
  if (out.empty()) failValue(flag, text, "no distances");
  for (double d : out) {
    if (d < 0.0) failValue(flag, text, "distances must be >= 0");
  }
  if (out.size() > kMaxDistances) failValue(flag, text, "too many distances");
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<double> parsePMins(const std::string& flag, const std::string& text) {
  std::vector<double> out;
  for (const std::string& item : splitOn(text, ',')) {
    const double p = parseNumber(flag, item);
    if (p < 0.0 || p > 1.0) failValue(flag, item, "p_min must be in [0, 1]");
    out.push_back(p);
  }
  if (out.empty()) failValue(flag, text, "empty list");
  return out;
}

std::vector<int> parseKMins(const std::string& flag, const std::string& text) {
  std::vector<int> out;
  for (const std::string& item : splitOn(text, ',')) {
    out.push_back(static_cast<int>(parseIntegerIn(flag, item, 1, 1000000)));
  }
  if (out.empty()) failValue(flag, text, "empty list");
  return out;
}

std::vector<double> parseBudgets(const std::string& flag, const std::string& text) {
  std::vector<double> out;
  for (const std::string& item : splitOn(text, ',')) {
    if (item == "none") {
      out.push_back(std::numeric_limits<double>::infinity());
      continue;
    }
    const double b = parseNumber(flag, item);
    if (b < 0.0) failValue(flag, item, "a budget must be >= 0 microseconds (or 'none')");
    out.push_back(b);
  }
  if (out.empty()) failValue(flag, text, "empty list");
  return out;
}

// Positive node-pair counts, each at most once (a repeat would measure one setting twice
// under one name).
std::vector<std::uint64_t> parseBudgetPairs(const std::string& flag, const std::string& text) {
  std::vector<std::uint64_t> out;
  for (const std::string& item : splitOn(text, ',')) {
    const long long n = parseInteger(flag, item);
    if (n < 1) failValue(flag, item, "a work budget must be a positive number of node pairs");
    const auto pairs = static_cast<std::uint64_t>(n);
    if (std::find(out.begin(), out.end(), pairs) != out.end()) failValue(flag, item, "listed twice");
    out.push_back(pairs);
  }
  if (out.empty()) failValue(flag, text, "empty list");
  return out;
}

const std::vector<std::string>& knownMethods() {
  static const std::vector<std::string> methods{"adb",       "exact",      "gimpact", "fcl",
                                                "exact-cut", "box-first", "root-boxes"};
  return methods;
}

std::string joined(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

std::vector<std::string> parseMethods(const std::string& flag, const std::string& text) {
  std::vector<std::string> out;
  const auto& known = knownMethods();
  for (const std::string& item : splitOn(text, ',')) {
    if (std::find(known.begin(), known.end(), item) == known.end()) {
      failValue(flag, item, "unknown method; known methods: " + joined(known));
    }
    if (std::find(out.begin(), out.end(), item) != out.end()) failValue(flag, item, "listed twice");
    out.push_back(item);
  }
  if (out.empty()) failValue(flag, text, "no methods");
  return out;
}

// exact-cut and box-first run only under finite time budgets: with none they would
// silently measure nothing.
void checkBudgetedMethods(const Options& o) {
  const bool finite = std::any_of(o.budgetsUs.begin(), o.budgetsUs.end(),
                                  [](double b) { return std::isfinite(b); });
  for (const char* name : {"exact-cut", "box-first"}) {
    if (!finite && std::find(o.methods.begin(), o.methods.end(), name) != o.methods.end()) {
      throw UsageError(std::string("--methods '") + name +
                       "': runs under the finite --budget-us values, and none is given");
    }
  }
}

// The names --model and --against-model accept: the benchmark's models, then the real-mesh
// ones (adb/support/mesh_generators.h).
std::vector<std::string> knownModels() {
  std::vector<std::string> names = adb::gen::modelNames();
  for (const std::string& n : adb::gen::realMeshModelNames()) names.push_back(n);
  return names;
}

bool isFixedModel(const std::string& name) {
  const std::vector<std::string> fixed = adb::gen::fixedModelNames();
  return std::find(fixed.begin(), fixed.end(), name) != fixed.end();
}

ModelSource parseModel(const std::string& flag, const std::string& text) {
  ModelSource s;
  s.kind = ModelSource::Kind::Generated;
  const std::size_t colon = text.find(':');
  s.name = text.substr(0, colon);
  const std::vector<std::string> names = knownModels();
  if (std::find(names.begin(), names.end(), s.name) == names.end()) {
    failValue(flag, text, "unknown model '" + s.name + "'; known models: " + joined(names));
  }
  if (isFixedModel(s.name)) {
    if (colon != std::string::npos) {
      failValue(flag, text, "'" + s.name + "' has one fixed resolution: give it without :N");
    }
    s.kind = ModelSource::Kind::Fixed;
    return s;
  }
  s.targetTriangles = kDefaultModelTriangles;
  if (colon != std::string::npos) {
    const long long n = parseInteger(flag, text.substr(colon + 1));
    if (n < static_cast<long long>(kMinModelTriangles) ||
        n > static_cast<long long>(kMaxModelTriangles)) {
      failValue(flag, text, "the triangle count must be between 1000 and 1000000");
    }
    s.targetTriangles = static_cast<std::size_t>(n);
  }
  return s;
}

ModelSource parseMeshFile(const std::string& flag, const std::string& value) {
  if (value.empty()) failValue(flag, value, "empty file name");
  ModelSource s;
  s.kind = ModelSource::Kind::File;
  s.path = value;
  return s;
}

// --against-mesh and --against-model: the second body of the case the --mesh or --model just
// before them began.
void pairWithLast(Options& o, const std::string& flag, const std::string& value,
                  const ModelSource& b) {
  if (o.cases.empty()) {
    failValue(flag, value,
              "no --mesh or --model before it: it names the model that the one given just "
              "before it is tested against");
  }
  StudyCase& last = o.cases.back();
  if (last.b) {
    failValue(flag, value,
              "'" + sourceLabel(last.a) + "' is already tested against '" +
                  sourceLabel(*last.b) + "': one --against-mesh or --against-model per "
                  "--mesh or --model");
  }
  last.b = b;
}

std::string joinArgs(int argc, const char* const* argv) {
  std::string line;
  for (int i = 0; i < argc; ++i) line += (i ? " " : "") + std::string(argv[i]);
  return line;
}

// A default list as --help shows it ("0.5,0.9,0.99"), from the Options defaults themselves.
template <typename T>
std::string listText(const std::vector<T>& items) {
  std::string out;
  for (const T& item : items) {
    std::ostringstream text;
    text << item;
    out += (out.empty() ? "" : ",") + text.str();
  }
  return out;
}

// What to measure: the models (or pairs of models), and the poses.
void addModelFlags(CLI::App& app, Options& o) {
  tools::addValueOption(app, "--mesh", "FILE",
                       "a mesh file (any format assimp reads); repeatable",
                       [&o](const std::string& value) {
                         o.cases.push_back(StudyCase{parseMeshFile("--mesh", value), {}});
                       });
  tools::addValueOption(app, "--model", "NAME[:N]",
                       "a generated model: " + joined(adb::gen::modelNames()) +
                           " (the benchmark's shapes) or slivers (long thin\n"
                           "triangles), about N triangles (1000..1000000, default 20000);\n"
                           "or, with one fixed resolution and no :N, " +
                           joined(adb::gen::fixedModelNames()) +
                           ". Repeatable.\nModels run in command-line order; at least one "
                           "--mesh or --model.",
                       [&o](const std::string& value) {
                         o.cases.push_back(StudyCase{parseModel("--model", value), {}});
                       });
  tools::addValueOption(app, "--against-mesh", "FILE",
                       "the second body of every query of the --mesh or --model just\n"
                       "before it: that model (A) is tested against this mesh file (B)\n"
                       "instead of a second copy of itself",
                       [&o](const std::string& value) {
                         pairWithLast(o, "--against-mesh", value,
                                      parseMeshFile("--against-mesh", value));
                       });
  tools::addValueOption(app, "--against-model", "NAME[:N]",
                       "the same with a generated model as B (names as --model).\n"
                       "A pair's rows are labelled 'A+B', their triangle count is A's\n"
                       "plus B's, and its distances are in the pair's unit: the mean of\n"
                       "the two models' units",
                       [&o](const std::string& value) {
                         pairWithLast(o, "--against-model", value,
                                      parseModel("--against-model", value));
                       });
  tools::addValueOption(
      app, "--poses", "distances|inside",
      "'distances': Zachmann's benchmark (both bodies rotated, box centres\n"
      "each of --distances apart along x); 'inside': FCL's robot in a room\n"
      "(A at the identity, B randomly rotated with its box centre uniformly\n"
      "random in A's bounding box; --rotations poses in all; the distance\n"
      "column holds the centres' distance, rounded to 0.1 unit)",
      [&o](const std::string& value) {
        if (value == "distances") {
          o.poses = PoseMode::Distances;
        } else if (value == "inside") {
          o.poses = PoseMode::Inside;
        } else {
          failValue("--poses", value, "expected distances or inside");
        }
      },
      "distances");
  tools::addValueOption(
      app, "--distances", "LIST", "numbers or ranges start:end:step, comma-separated",
      [&o](const std::string& value) {
        o.distances = parseDistances("--distances", value);
        o.distancesGiven = true;
      },
      kDefaultDistances);
  tools::addIntegerOption(app, "--rotations", o.rotations, 1, 10000000,
                         "random orientation pairs per distance (--poses inside: poses\n"
                         "in all)");
  tools::addValueOption(
      app, "--seed", "N", "seed of the random orientations",
      [&o](const std::string& value) {
        const long long s = parseInteger("--seed", value);
        if (s < 0) failValue("--seed", value, "the seed must be >= 0");
        o.seed = static_cast<std::uint64_t>(s);
      },
      std::to_string(o.seed));
}

// Which methods answer, and the ADB settings swept.
void addMethodFlags(CLI::App& app, Options& o) {
  tools::addValueOption(
      app, "--methods", "LIST",
      "adb (every p_min x k_min x budget), exact (the ADB-tree's exact\n"
      "mode), gimpact (Bullet GImpact, full contact set), fcl (FCL\n"
      "OBBRSS, first contact); opt-in baselines that show whether\n"
      "ADB's probability pays for itself:\n"
      "exact-cut (exact mode under each finite --budget-us; a cut\n"
      "query answers what the core returns), box-first (the same tree\n"
      "searched largest box overlap first, no probability, under each\n"
      "finite --budget-us; cut: 'collides' while boxes still overlap,\n"
      "confidence 0.5), root-boxes ('collides' whenever the root boxes\n"
      "overlap, confidence 0.5)",
      [&o](const std::string& value) { o.methods = parseMethods("--methods", value); },
      listText(o.methods));
  tools::addValueOption(
      app, "--p-min", "LIST", "ADB quality targets to sweep: probabilities in [0, 1]",
      [&o](const std::string& value) { o.pMins = parsePMins("--p-min", value); },
      listText(o.pMins));
  tools::addValueOption(
      app, "--k-min", "LIST", "ADB quality targets to sweep: node pair counts >= 1",
      [&o](const std::string& value) { o.kMins = parseKMins("--k-min", value); },
      listText(o.kMins));
  tools::addValueOption(
      app, "--budget-us", "LIST",
      "wall-clock budgets in microseconds for adb, exact-cut and\n"
      "box-first; 'none' = no budget (adb only)",
      [&o](const std::string& value) { o.budgetsUs = parseBudgets("--budget-us", value); },
      kDefaultBudgets);
  // A build setting, but it changes what ADB's probabilities are made of: the paper compares
  // both counts (+0.2 points of error for the approximate one).
  app.add_flag_callback("--exact-counting", [&o] { o.exactCounting = true; },
                        "build the ADB-trees with exact cell counts (every triangle clipped\n"
                        "into every ancestor's grid, ~20x slower) instead of the\n"
                        "approximate ones (paper section 3.4)")
      ->disable_flag_override();
  tools::addValueOption(
      app, "--adb-key", "eq3|table",
      "what orders ADB's queue: 'table' (a table approximating Eq. 3,\n"
      "bucket queue) or 'eq3' (Eq. 3 itself, binary heap): the same\n"
      "acceptances, another order and cost",
      [&o](const std::string& value) {
        if (value == "table") {
          o.adbKey = AdbKey::Table;
        } else if (value == "eq3") {
          o.adbKey = AdbKey::Eq3;
        } else {
          failValue("--adb-key", value, "expected eq3 or table");
        }
      },
      o.adbKey == AdbKey::Table ? "table" : "eq3");
  tools::addValueOption(
      app, "--budget-pairs", "LIST",
      "ADB work budgets in node pairs, positive integers (default: none);\n"
      "each N adds the methods 'adb-work:N', one per p_min x k_min",
      [&o](const std::string& value) {
        o.budgetPairs = parseBudgetPairs("--budget-pairs", value);
      });
}

// How each query is timed and where the results go.
void addRunFlags(CLI::App& app, Options& o) {
  tools::addIntegerOption(app, "--repeats", o.repeats, 1, 1000, "timed runs per query");
  tools::addValueOption(
      app, "--out", "DIR",
      "output directory: queries.csv, summary.csv, summary.md,\n"
      "reliability.csv, cells.csv, distances.csv, plots",
      [&o](const std::string& value) {
        if (value.empty()) failValue("--out", value, "empty directory name");
        o.outDir = value;
      },
      o.outDir);
  // A plain switch: "--no-plots=false" would read as a double negative.
  app.add_flag_callback("--no-plots", [&o] { o.plots = false; },
                        "do not run studies/tradeoff/plot_tradeoff.py")
      ->disable_flag_override();
  app.add_flag_callback("--no-warmup", [&o] { o.warmup = false; },
                        "time each query cold: no untimed run before the timed ones (what a "
                        "batch of different poses meets; benchmarks/python compares with it)")
      ->disable_flag_override();
}

const char* const kAbout =
    "adb-tradeoff: accuracy vs time of ADB-tree queries against exact peers, on Zachmann's\n"
    "benchmark: two copies of each model, bounding-box centres DISTANCE apart (unit: half the\n"
    "largest edge of the model's bounding box), --rotations seeded random orientations of both\n"
    "copies per distance; every method answers the same poses. A model given\n"
    "--against-mesh/--against-model B is tested against B instead of a copy of itself\n"
    "(unit: the mean of the two models' units); --poses inside places B anywhere in the\n"
    "model's bounding box instead.";

const char* const kPolicy =
    "Timing: every method's data structures are built once per model (both models of a\n"
    "pair), untimed. Each query\n"
    "runs once untimed (warm caches, as for a pair queried frame after frame; not with\n"
    "--no-warmup), then --repeats\n"
    "times, each timed with std::chrono::steady_clock around the call; the fastest run is\n"
    "the query's time (the machine is shared: interference only adds time) and its answer is\n"
    "recorded. Methods are interleaved pose by pose, so a burst of noise hits all alike.\n"
    "GImpact: collision margin 0; its algorithm object is created once per model (as a\n"
    "Bullet world keeps one per pair) and each query times processCollision, which always\n"
    "computes the full contact set.\n"
    "\n"
    "Calibration: reliability.csv bins the confidence of every method with an estimate (adb,\n"
    "adb-work:N, exact-cut; 'adb-pooled' pools adb and adb-work) into 10 bins of width 0.1\n"
    "and gives, per bin, the mean confidence and the fraction of right answers (against\n"
    "exact, else fcl; root boxes overlapping only). summary.csv's ece is the expected\n"
    "calibration error sum_b (count_b / N) |fraction_right_b - mean_confidence_b|.\n"
    "summary.md ends with the smallest budgets that reach 5 % and 1 % error.\n"
    "\n"
    "Exit status: 0 done, 2 usage error, 1 input error (unreadable mesh, bad geometry); on\n"
    "an input error the results of the models before it are written first.\n";

// Every flag of the tool on `app`, writing into `o`; --help is made from the same calls,
// so it lists every flag.
void describe(CLI::App& app, Options& o) {
  app.description(kAbout);
  app.footer(kPolicy);
  addModelFlags(app, o);
  addMethodFlags(app, o);
  addRunFlags(app, o);
}

}  // namespace

Options parseOptions(int argc, const char* const* argv) {
  Options o;
  o.commandLine = joinArgs(argc, argv);
  o.distances = parseDistances("--distances", kDefaultDistances);
  o.budgetsUs = parseBudgets("--budget-us", kDefaultBudgets);
  CLI::App app{"", "adb-tradeoff"};
  describe(app, o);
  if (tools::parseOrThrow(app, argc, argv)) {
    o.help = true;
    return o;
  }
  if (o.cases.empty()) {
    throw UsageError("nothing to measure: give at least one --mesh FILE or --model NAME");
  }
  if (o.poses == PoseMode::Inside && o.distancesGiven) {
    throw UsageError(
        "--distances: not used with --poses inside, which places B's centre anywhere in A's "
        "bounding box (give --rotations for the number of poses)");
  }
  checkBudgetedMethods(o);
  return o;
}

std::string fileStem(const std::string& path) {
  const std::size_t slash = path.find_last_of("/\\");
  std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  const std::size_t dot = base.find_last_of('.');
  if (dot != std::string::npos && dot > 0) base = base.substr(0, dot);
  return base.empty() ? path : base;
}

std::string sourceLabel(const ModelSource& source) {
  return source.kind == ModelSource::Kind::File ? fileStem(source.path) : source.name;
}

std::string usageText() {
  Options defaults;
  CLI::App app{"", "adb-tradeoff"};
  describe(app, defaults);
  return app.help();
}

}  // namespace adb::tradeoff
