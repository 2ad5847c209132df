// adb-calibrate: fits the collision estimate (adb/core/collision_estimate.h) on generated
// models and pairs of models, and checks it on pairs it never saw, at the budgets users set.
//
// The fit set: the six generated models at --triangles, the sliver cylinder, the pipe bundle
// at 400 triangles and the 296-triangle robot arm, each against a copy of itself; and pairs of
// different models: the arm anywhere in the generated room (FCL's robot-in-a-room poses), a
// dense model against another, slivers against a dense model, the arm against the pipes.
// Checked, never fitted: two generated pairs (the pipes anywhere in the room, the sphere
// against the slivers) and whatever --mesh, --pair and --inside name.
//
// For every pose (Zachmann's distances 0.4 to 2.0 with random rotations, or anywhere inside the
// environment's box) whose root boxes overlap:
// - the fit's samples: each ADB quality setting run as one Traversal stepped towards work
//   budgets of 1, 2, 4, ... node pairs; every budget stop is a sample (its evidence's features
//   and the exact answer), every quality stop (k_min, or a queue emptied by pruning) a sample
//   of whether the paper's answer is right;
// - the check: QuerySettings' defaults under each of the budgets users set (8, 32, 128 and 512
//   node pairs, 5 and 20 microseconds), one query each, as collide() runs it: its answer and
//   confidence as the library gives them, and its evidence, to judge freshly fitted weights.
// The budget model is a logistic regression (Newton's method, evidence weights >= 0, each
// case weighted equally) followed by a monotone recalibration (pool-adjacent-violators); the
// quality model a logistic regression of whether the paper's answer is right.
//
// It prints the weights and the map as the C++ lines collision_estimate.cpp holds, then per
// case and budget the expected calibration error (10 bins, studies/tradeoff/calibration.h),
// the wrong answers and the wrong answers given with confidence >= 0.99 (both as shares of all
// answers), as the library answers and as the fresh fit would; writes reliability.csv and
// reliability.png (a reliability diagram per budget) into --out.
//
//   adb-calibrate [--triangles N] [--rotations N] [--mesh FILE ...] [--pair A,B ...]
//                 [--inside ENV,BODY ...] [--samples FILE] [--out DIR] [--no-plots]
#include <CLI/CLI.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "adb/core/collision_estimate.h"
#include "adb/core/node_triangles.h"
#include "adb/core/open_pair_estimate.h"
#include "adb/core/triangle_test.h"
#include "adb/core/query.h"
#include "adb/core/tree.h"
#include "adb/io/mesh_file.h"
#include "adb/support/benchmark_poses.h"
#include "adb/support/mesh_generators.h"
#include "logistic_fit.h"
#include "shared/command_line.h"
#include "tradeoff/calibration.h"
#include "tradeoff/plots.h"

namespace {

using adb::calibrate::CaseSamples;
using adb::calibrate::MonotoneMap;
using adb::calibrate::Sample;
using Features = std::array<double, adb::kEstimateFeatures>;

template <std::size_t N>
std::vector<double> toVector(const std::array<double, N>& f) {
  return std::vector<double>(f.begin(), f.end());
}
template <std::size_t N>
std::array<double, N> toArray(const std::vector<double>& w) {
  std::array<double, N> out{};
  std::copy_n(w.begin(), std::min(w.size(), N), out.begin());
  return out;
}

constexpr int kCheckpoints = 14;  // work budgets 2^0 .. 2^13 node pairs
struct Quality {
  double pMin;
  int kMin;
  bool papersRules;  // p = 0 pairs pruned, any inner pair accepted (not the defaults)
};
// The defaults queue p = 0 pairs, so a queue never empties by pruning under them: the paper's
// rules, which users may still set, give the fit those stops.
constexpr Quality kQualities[] = {
    {0.99, 10, false}, {0.9, 5, false}, {0.9, 1, false}, {0.5, 1, false}, {0.99, 10, true}};

// The budgets the check runs at QuerySettings' defaults (issue 43's targets).
struct CheckBudget {
  const char* label;
  adb::StepBudget budget;
};
const CheckBudget kCheckBudgets[] = {
    {"8 pairs", {8, std::numeric_limits<double>::infinity()}},
    {"32 pairs", {32, std::numeric_limits<double>::infinity()}},
    {"128 pairs", {128, std::numeric_limits<double>::infinity()}},
    {"512 pairs", {512, std::numeric_limits<double>::infinity()}},
    {"5 us", {std::numeric_limits<std::uint64_t>::max(), 5.0}},
    {"20 us", {std::numeric_limits<std::uint64_t>::max(), 20.0}},
};
constexpr int kCheckBudgetCount = static_cast<int>(std::size(kCheckBudgets));

// One query of the check: how it stopped, what the library answered, and what a fresh fit
// needs to answer it again.
struct CheckQuery {
  enum class Kind { Certain, Budget, Quality } kind = Kind::Certain;
  bool reachedKMin = false;
  bool libraryCollides = false;
  double libraryConfidence = 1.0;
  Features f{};
  bool truth = false;
};

struct CaseResult {
  std::string name;
  bool fit = false;
  CaseSamples budget, quality, openPairs;
  std::array<std::vector<CheckQuery>, kCheckBudgetCount> check;
};

// How the second body is placed: Zachmann's distances, or anywhere inside the first's box
// (FCL's robot in a room: adb::insidePoses).
enum class Placement { Distances, Inside };

struct Case {
  std::string name;
  adb::TriangleMesh a, b;
  Placement placement = Placement::Distances;
  bool fit = false;
};

// The triangles of a tree-order range posed in the world, each with its box.
struct PosedTriangles {
  std::vector<std::array<adb::Vec3, 3>> corners;
  std::vector<adb::Aabb> boxes;
};
PosedTriangles posed(const adb::AdbTree& tree, const adb::Pose& pose,
                     std::pair<std::uint32_t, std::uint32_t> range) {
  PosedTriangles out;
  for (std::uint32_t i = range.first; i < range.second; ++i) {
    std::array<adb::Vec3, 3> v;
    adb::Aabb box;
    for (int k = 0; k < 3; ++k) {
      v[k] = pose.rotation * (tree.localVertices()[tree.triangles()[i][k]] + tree.origin()) +
             pose.translation;
      box.grow(v[k]);
    }
    out.corners.push_back(v);
    out.boxes.push_back(box);
  }
  return out;
}

// Whether a triangle below node a meets one below node b (brute force, boxes first); nothing
// for pairs of more than kMaxLabelTests triangle pairs, which would take seconds.
constexpr std::uint64_t kMaxLabelTests = 1u << 20;
std::optional<bool> nodesTouch(const adb::AdbTree& ta, const adb::Pose& pa, std::uint32_t a,
                               const adb::AdbTree& tb, const adb::Pose& pb, std::uint32_t b) {
  const auto ra = adb::trianglesBelow(ta, a), rb = adb::trianglesBelow(tb, b);
  if (std::uint64_t{ra.second - ra.first} * (rb.second - rb.first) > kMaxLabelTests) {
    return std::nullopt;
  }
  const PosedTriangles x = posed(ta, pa, ra), y = posed(tb, pb, rb);
  for (std::size_t i = 0; i < x.corners.size(); ++i) {
    for (std::size_t j = 0; j < y.corners.size(); ++j) {
      if ((x.boxes[i].lo.array() > y.boxes[j].hi.array()).any() ||
          (y.boxes[j].lo.array() > x.boxes[i].hi.array()).any()) {
        continue;
      }
      const auto& u = x.corners[i];
      const auto& v = y.corners[j];
      if (adb::trianglesIntersect(u[0], u[1], u[2], v[0], v[1], v[2])) return true;
    }
  }
  return false;
}

// A few open pairs of a budget stop at the defaults, each labelled by whether its triangles
// meet: the samples of the open-pair estimate (adb/core/open_pair_estimate.h), which decides
// Bullet's plausible contacts.
constexpr int kOpenPairsPerStop = 4;
void sampleOpenPairs(const adb::AdbTree& treeA, const adb::AdbTree& treeB,
                     const adb::PosePair& p, const adb::Traversal& t, int checkpoint,
                     std::mt19937_64& rng, CaseSamples& out) {
  const std::vector<adb::OpenPair>& open = t.openPairs();
  if (open.empty()) return;
  std::uniform_int_distribution<std::size_t> pick(0, open.size() - 1);
  for (int k = 0; k < kOpenPairsPerStop; ++k) {
    const adb::OpenPair& o = open[pick(rng)];
    const std::optional<bool> touch = nodesTouch(treeA, p.a, o.a, treeB, p.b, o.b);
    if (!touch) continue;
    out.samples.push_back(Sample{toVector(adb::openPairFeatures(o, treeA, treeB)), *touch,
                                 checkpoint});
  }
}

// The fit's samples of one pose under one quality setting.
void sampleTraversal(const adb::AdbTree& treeA, const adb::AdbTree& treeB,
                     const adb::PosePair& p, const Quality& q, bool truth, std::mt19937_64& rng,
                     CaseResult& out) {
  adb::QuerySettings s;
  s.pMin = q.pMin;
  s.kMin = q.kMin;
  if (q.papersRules) {
    s.pruneImprobable = true;
    s.minTrianglesToAccept = 0;
  }
  adb::Traversal t(treeA, p.a, treeB, p.b, s);
  for (int c = 0; c < kCheckpoints; ++c) {
    // A step makes at least one expansion, so the traversal may already be past this budget:
    // its state was sampled then, and is not counted twice.
    const std::uint64_t target = std::uint64_t{1} << c;
    const std::uint64_t done = t.result().nodePairs;
    if (target <= done) continue;
    t.step(adb::StepBudget{target - done});
    if (t.done()) {
      // Ended on its own: at k_min, or with a queue emptied by pruning (an exact hit or an
      // exhaustive traversal is certain, not a sample). The label is whether the paper's
      // answer is right: the estimate keeps that answer and says how sure it is.
      const adb::QueryResult& r = t.result();
      adb::Evidence e = t.evidence();
      const bool reached = r.stop == adb::StopReason::QualityReached;
      if (reached || (r.stop == adb::StopReason::Completed && e.prunedDoubt > 0.0)) {
        e.quality = true;
        e.reachedKMin = reached;
        out.quality.samples.push_back(Sample{toVector(adb::estimateFeatures(e)), reached == truth, c});
      }
      return;
    }
    out.budget.samples.push_back(Sample{toVector(adb::estimateFeatures(t.evidence())), truth, c});
    if (q.pMin == 0.99 && q.kMin == 10 && !q.papersRules) {
      sampleOpenPairs(treeA, treeB, p, t, c, rng, out.openPairs);
    }
  }
}

// One check query: the defaults under `budget`, run once as collide() runs it.
CheckQuery checkQuery(const adb::AdbTree& treeA, const adb::AdbTree& treeB,
                      const adb::PosePair& p, const adb::StepBudget& budget, bool truth) {
  adb::Traversal t(treeA, p.a, treeB, p.b, adb::QuerySettings{});
  const adb::QueryResult& r = t.step(budget);
  CheckQuery q;
  q.truth = truth;
  q.libraryCollides = r.collides;
  q.libraryConfidence = r.confidence;
  const bool certain = r.stop == adb::StopReason::ExactHit ||
                       (r.stop == adb::StopReason::Completed && r.confidence >= 1.0);
  if (!certain) {
    adb::Evidence e = t.evidence();
    e.quality = !adb::isBudgetStop(r.stop);
    e.reachedKMin = r.stop == adb::StopReason::QualityReached;
    q.kind = e.quality ? CheckQuery::Kind::Quality : CheckQuery::Kind::Budget;
    q.reachedKMin = e.reachedKMin;
    q.f = adb::estimateFeatures(e);
  }
  return q;
}

CaseResult collect(const Case& c, int rotations) {
  const adb::AdbTree treeA(c.a), treeB(c.b);
  adb::QueryScratch scratch;
  adb::QuerySettings exact;
  exact.mode = adb::QueryMode::Exact;
  std::mt19937_64 rng(1);
  CaseResult m;
  m.name = c.name;
  m.fit = c.fit;
  m.budget.name = m.quality.name = m.openPairs.name = c.name;
  // Inside poses have no distances: as many poses in all as the distances give.
  const int steps = c.placement == Placement::Inside ? 1 : 17;
  const int perStep = c.placement == Placement::Inside ? 17 * rotations : rotations;
  for (int step = 0; step < steps; ++step) {
    for (int r = 0; r < perStep; ++r) {
      const adb::PosePair p =
          c.placement == Placement::Inside
              ? adb::insidePoses(c.a.bounds(), c.b.bounds(), rng)
              : adb::benchmarkPoses(c.a.bounds(), c.b.bounds(), 0.4 + 0.1 * step, rng);
      const adb::QueryResult truth = adb::collide(treeA, p.a, treeB, p.b, exact, scratch);
      if (truth.nodePairs <= 1 && !truth.collides) continue;  // root boxes apart: not counted
      for (const Quality& q : kQualities) {
        sampleTraversal(treeA, treeB, p, q, truth.collides, rng, m);
      }
      for (int b = 0; b < kCheckBudgetCount; ++b) {
        m.check[b].push_back(checkQuery(treeA, treeB, p, kCheckBudgets[b].budget, truth.collides));
      }
    }
  }
  std::fprintf(stderr, "%s (%s): %zu poses, %zu budget stops, %zu quality stops\n",
               c.name.c_str(), c.fit ? "fit" : "check", m.check[0].size(),
               m.budget.samples.size(), m.quality.samples.size());
  return m;
}

// The estimate a fit gives: weights, map and quality weights.
struct Estimate {
  adb::EstimateWeights budget{}, quality{};
  MonotoneMap map;
  double collisionProbability(const CheckQuery& q) const {
    if (q.kind == CheckQuery::Kind::Budget) {
      return adb::monotoneMap(adb::logisticEstimate(q.f, budget), map.x.data(), map.y.data(),
                              static_cast<int>(map.x.size()));
    }
    const double right = adb::logisticEstimate(q.f, quality);
    return q.reachedKMin ? right : 1.0 - right;
  }
};

// The check queries' answers judged: by the library's own answers, or by `fresh`.
std::vector<adb::tradeoff::JudgedAnswer> judged(const std::vector<CheckQuery>& queries,
                                                const Estimate* fresh) {
  std::vector<adb::tradeoff::JudgedAnswer> out;
  out.reserve(queries.size());
  for (const CheckQuery& q : queries) {
    bool answer = q.libraryCollides;
    double confidence = q.libraryConfidence;
    if (fresh && q.kind != CheckQuery::Kind::Certain) {
      const double p = fresh->collisionProbability(q);
      answer = p >= 0.5;
      confidence = answer ? p : 1.0 - p;
    }
    out.push_back({confidence, answer == q.truth});
  }
  return out;
}

struct Judgement {
  double ece = 0.0, wrongPct = 0.0, confidentWrongPct = 0.0;
};

Judgement judge(const std::vector<adb::tradeoff::JudgedAnswer>& answers) {
  Judgement j;
  if (answers.empty()) return j;
  int wrong = 0, confidentWrong = 0;
  for (const auto& a : answers) {
    wrong += a.right ? 0 : 1;
    confidentWrong += !a.right && a.confidence >= 0.99 ? 1 : 0;
  }
  const double n = static_cast<double>(answers.size());
  j.ece = adb::tradeoff::expectedCalibrationError(adb::tradeoff::reliabilityBins(answers));
  j.wrongPct = 100.0 * wrong / n;
  j.confidentWrongPct = 100.0 * confidentWrong / n;
  return j;
}

// One row per case: per budget "ECE / wrong % / wrong at >= 0.99 %".
void printCheckTable(const char* title, const std::vector<CaseResult>& cases,
                     const Estimate* fresh) {
  std::printf("\n%s\n\n| case | set | poses |", title);
  for (const CheckBudget& b : kCheckBudgets) std::printf(" %s |", b.label);
  std::printf("\n|---|---|---|");
  for (int b = 0; b < kCheckBudgetCount; ++b) std::printf("---|");
  std::printf("\n");
  for (const CaseResult& c : cases) {
    std::printf("| %s | %s | %zu |", c.name.c_str(), c.fit ? "fit" : "check", c.check[0].size());
    for (int b = 0; b < kCheckBudgetCount; ++b) {
      const Judgement j = judge(judged(c.check[b], fresh));
      std::printf(" %.3f / %.1f / %.2f |", j.ece, j.wrongPct, j.confidentWrongPct);
    }
    std::printf("\n");
  }
  std::printf("\n(each cell: ECE / wrong answers %% / wrong answers given with confidence >= "
              "0.99, %% of all answers)\n");
}

// A file opened for writing; throws (main reports it) when it cannot be.
std::FILE* openForWriting(const std::string& path) {
  std::FILE* out = std::fopen(path.c_str(), "w");
  if (!out) throw std::runtime_error("cannot write " + path);
  return out;
}

// The reliability diagrams of the library's answers: per case and budget, and pooled per set.
void writeReliability(const std::string& path, const std::vector<CaseResult>& cases) {
  std::FILE* out = openForWriting(path);
  std::fprintf(out, "set,case,budget,ece,bin_lo,bin_hi,count,mean_confidence,fraction_right\n");
  const auto write = [&](const char* set, const std::string& name, int b,
                         const std::vector<adb::tradeoff::JudgedAnswer>& answers) {
    if (answers.empty()) return;
    const adb::tradeoff::ReliabilityBins bins = adb::tradeoff::reliabilityBins(answers);
    const double ece = adb::tradeoff::expectedCalibrationError(bins);
    for (const auto& bin : bins) {
      if (bin.count == 0) continue;
      std::fprintf(out, "%s,%s,%s,%.4f,%.1f,%.1f,%zu,%.4f,%.4f\n", set, name.c_str(),
                   kCheckBudgets[b].label, ece, bin.lo, bin.hi, bin.count, bin.meanConfidence,
                   bin.fractionRight);
    }
  };
  for (int b = 0; b < kCheckBudgetCount; ++b) {
    std::vector<adb::tradeoff::JudgedAnswer> pooled[2];
    for (const CaseResult& c : cases) {
      const auto answers = judged(c.check[b], nullptr);
      write(c.fit ? "fit" : "check", c.name, b, answers);
      pooled[c.fit ? 0 : 1].insert(pooled[c.fit ? 0 : 1].end(), answers.begin(), answers.end());
    }
    write("fit", "all fit", b, pooled[0]);
    write("check", "all check", b, pooled[1]);
  }
  std::fclose(out);
}

// Every fit sample as CSV (set, case, checkpoint, features, truth): for looking at the data.
void writeSamples(const std::string& path, const std::vector<CaseResult>& cases) {
  std::FILE* out = openForWriting(path);
  std::fprintf(out, "set,model,checkpoint");
  for (int i = 0; i < adb::kEstimateFeatures; ++i) std::fprintf(out, ",f%d", i);
  std::fprintf(out, ",truth\n");
  for (const CaseResult& c : cases) {
    for (const Sample& s : c.budget.samples) {
      std::fprintf(out, "%s,%s,%d", c.fit ? "fit" : "check", c.name.c_str(), s.checkpoint);
      for (double f : s.f) std::fprintf(out, ",%.9g", f);
      std::fprintf(out, ",%d\n", s.truth ? 1 : 0);
    }
  }
  std::fclose(out);
}

void printWeights(const char* name, const adb::EstimateWeights& w) {
  std::printf("constexpr EstimateWeights %s{", name);
  for (int i = 0; i < adb::kEstimateFeatures; ++i) std::printf("%s%.6g", i ? ", " : "", w[i]);
  std::printf("};\n");
}

void printMap(const MonotoneMap& map) {
  std::printf("constexpr int kBudgetMapKnots = %zu;\n", map.x.size());
  for (const auto* v : {&map.x, &map.y}) {
    std::printf("constexpr double kBudgetMap%s[] = {", v == &map.x ? "X" : "Y");
    for (std::size_t i = 0; i < v->size(); ++i) std::printf("%s%.6g", i ? ", " : "", (*v)[i]);
    std::printf("};\n");
  }
}

struct Options {
  std::size_t triangles = 20000;
  int rotations = 40;
  std::vector<std::string> meshes;
  std::vector<std::pair<std::string, std::string>> pairs, inside;
  std::string samplesPath;
  std::string outDir = "build/calibrate";
  bool plots = true;
  int knots = 20;
};

std::pair<std::string, std::string> twoFiles(const std::string& option,
                                             const std::string& value) {
  const std::size_t comma = value.find(',');
  if (comma == std::string::npos) adb::tools::failValue(option, value, "expected FILE_A,FILE_B");
  std::pair<std::string, std::string> files{value.substr(0, comma), value.substr(comma + 1)};
  for (const std::string& f : {files.first, files.second}) {
    // Checked here so that a typo fails before minutes of fitting.
    if (!std::filesystem::is_regular_file(f)) adb::tools::failValue(option, f, "no such file");
  }
  return files;
}

void addOptions(CLI::App& app, Options& o) {
  app.description(
      "adb-calibrate: fits the collision estimate (adb/core/collision_estimate.h) on generated\n"
      "models and pairs of models, checks it on pairs it never saw at the budgets users set,\n"
      "prints the weights as C++ and the calibration per case and budget, and draws a\n"
      "reliability diagram per budget (docs/probability-model.md).");
  constexpr long long kNoLimit = std::numeric_limits<long long>::max();
  adb::tools::addIntegerOption(app, "--triangles", o.triangles, 1000, kNoLimit,
                               "about this many triangles per dense generated model");
  adb::tools::addIntegerOption(app, "--rotations", o.rotations, 1,
                               std::numeric_limits<int>::max(),
                               "random orientation pairs per distance (0.4 to 2.0 by 0.1); "
                               "inside poses: 17 times as many in all");
  adb::tools::addValueOption(app, "--mesh", "FILE",
                             "check (not fit) on this mesh file against a copy of itself; "
                             "repeatable",
                             [&o](const std::string& path) {
                               if (!std::filesystem::is_regular_file(path)) {
                                 adb::tools::failValue("--mesh", path, "no such file");
                               }
                               o.meshes.push_back(path);
                             });
  adb::tools::addValueOption(app, "--pair", "A,B",
                             "check on mesh file A against mesh file B at the distances; "
                             "repeatable",
                             [&o](const std::string& v) { o.pairs.push_back(twoFiles("--pair", v)); });
  adb::tools::addValueOption(app, "--inside", "ENV,BODY",
                             "check on mesh file BODY anywhere inside ENV's box (a robot in a "
                             "room); repeatable",
                             [&o](const std::string& v) {
                               o.inside.push_back(twoFiles("--inside", v));
                             });
  adb::tools::addValueOption(app, "--samples", "FILE",
                             "write every budget-stop sample (set, case, checkpoint, features, "
                             "truth) as CSV",
                             [&o](const std::string& path) { o.samplesPath = path; });
  adb::tools::addValueOption(app, "--out", "DIR",
                             "where reliability.csv and reliability.png go",
                             [&o](const std::string& dir) { o.outDir = dir; }, o.outDir);
  app.add_flag_callback("--no-plots", [&o] { o.plots = false; },
                        "write reliability.csv only (no python3 run)")
      ->disable_flag_override();
}

std::string stem(const std::string& path) { return std::filesystem::path(path).stem().string(); }

// A copy of `mesh` scaled by `factor` about the origin.
adb::TriangleMesh scaled(const adb::TriangleMesh& mesh, double factor) {
  std::vector<adb::Vec3> vertices = mesh.vertices();
  for (adb::Vec3& v : vertices) v *= factor;
  return adb::TriangleMesh(std::move(vertices), mesh.triangles());
}

std::vector<Case> casesOf(const Options& o) {
  using adb::gen::makeFixedModel;
  using adb::gen::makeModel;
  std::vector<Case> cases;
  const auto add = [&](std::string name, adb::TriangleMesh a, adb::TriangleMesh b,
                       Placement placement, bool fit) {
    cases.push_back(Case{std::move(name), std::move(a), std::move(b), placement, fit});
  };
  const auto copies = [&](const std::string& name, const adb::TriangleMesh& mesh, bool fit) {
    add(name, mesh, mesh, Placement::Distances, fit);
  };
  for (const char* name : {"knot", "pipes", "gears", "lock", "torus", "sphere", "slivers"}) {
    copies(name, makeModel(name, o.triangles), true);
  }
  // Meshes as they come (issue 37): few large triangles, as robot and environment models are.
  copies("pipes-400", makeModel("pipes", 400), true);
  copies("robot", makeFixedModel("robot"), true);
  // Two different models (issue 43): a low-poly environment with a robot inside, dense against
  // dense, slivers against dense, low-poly against low-poly.
  add("room+robot", makeFixedModel("room"), makeFixedModel("robot"), Placement::Inside, true);
  add("knot+gears", makeModel("knot", o.triangles), makeModel("gears", o.triangles / 4),
      Placement::Distances, true);
  add("slivers+lock", makeModel("slivers", o.triangles / 4), makeModel("lock", o.triangles),
      Placement::Distances, true);
  add("robot+pipes-400", makeFixedModel("robot"), makeModel("pipes", 400), Placement::Distances,
      true);
  // Bodies of different sizes: E[X] is counted at the coarser node's cells, so it reads lower
  // for the same contact.
  add("knot+gears/6", makeModel("knot", o.triangles),
      scaled(makeModel("gears", o.triangles / 4), 1.0 / 6.0), Placement::Distances, true);
  // Checked, never fitted: another body in the room, and a pair of shapes never paired.
  add("room+pipes-400", makeFixedModel("room"), makeModel("pipes", 400), Placement::Inside,
      false);
  add("sphere+slivers", makeModel("sphere", o.triangles / 4), makeModel("slivers", o.triangles),
      Placement::Distances, false);
  for (const std::string& path : o.meshes) {
    const adb::TriangleMesh mesh = adb::io::loadMesh(path);
    copies(stem(path), mesh, false);
  }
  for (const auto& [pa, pb] : o.pairs) {
    add(stem(pa) + "+" + stem(pb), adb::io::loadMesh(pa), adb::io::loadMesh(pb),
        Placement::Distances, false);
  }
  for (const auto& [env, body] : o.inside) {
    add(stem(env) + "+" + stem(body) + " (inside)", adb::io::loadMesh(env),
        adb::io::loadMesh(body), Placement::Inside, false);
  }
  return cases;
}

// Quality stops per case: the fitted estimate's ECE and wrong answers against the paper's
// answer alone (the label says whether the paper's answer is right).
void printQuality(const std::vector<CaseResult>& cases, const adb::EstimateWeights& w) {
  std::printf("\nQuality stops of the fit's settings (k_min reached, or the queue emptied by "
              "pruning):\n\n| case | set | stops | ECE | wrong %% | paper's rule wrong %% |\n"
              "|---|---|---|---|---|---|\n");
  for (const CaseResult& c : cases) {
    std::vector<adb::tradeoff::JudgedAnswer> answers;
    int paperWrong = 0;
    for (const Sample& s : c.quality.samples) {
      const double right = adb::logisticEstimate(toArray<adb::kEstimateFeatures>(s.f), w);
      answers.push_back({std::max(right, 1.0 - right), (right >= 0.5) == s.truth});
      paperWrong += s.truth ? 0 : 1;
    }
    const Judgement j = judge(answers);
    const double n = static_cast<double>(std::max<std::size_t>(1, answers.size()));
    std::printf("| %s | %s | %zu | %.3f | %.1f | %.1f |\n", c.name.c_str(),
                c.fit ? "fit" : "check", answers.size(), j.ece, j.wrongPct,
                100.0 * paperWrong / n);
  }
}

// Open pairs per case: ECE and wrong answers of the open-pair estimate (the answer "touch" where
// it is >= 0.5), and of the priority key read as a probability (what Bullet read before), and
// how often pairs accepted at 0.9 touch.
void printOpenPairs(const std::vector<CaseResult>& cases, const adb::OpenPairWeights& w) {
  std::printf("\nOpen pairs of budget stops at the defaults (labelled by brute force):\n\n"
              "| case | set | pairs | touching %% | ECE | ECE of the key | accepted at 0.9 | "
              "of them touching %% |\n|---|---|---|---|---|---|---|---|\n");
  for (const CaseResult& c : cases) {
    std::vector<adb::tradeoff::JudgedAnswer> fitted, key;
    int touching = 0, accepted = 0, acceptedTouching = 0;
    for (const Sample& s : c.openPairs.samples) {
      const double p = adb::openPairProbability(toArray<adb::kOpenPairFeatures>(s.f), w);
      const double k = s.f[adb::kOpenPairFeatures - 1];  // the key
      fitted.push_back({std::max(p, 1.0 - p), (p >= 0.5) == s.truth});
      key.push_back({std::max(k, 1.0 - k), (k >= 0.5) == s.truth});
      touching += s.truth ? 1 : 0;
      if (p >= 0.9) {
        ++accepted;
        acceptedTouching += s.truth ? 1 : 0;
      }
    }
    const double n = static_cast<double>(std::max<std::size_t>(1, fitted.size()));
    std::printf("| %s | %s | %zu | %.1f | %.3f | %.3f | %d | %.1f |\n", c.name.c_str(),
                c.fit ? "fit" : "check", fitted.size(), 100.0 * touching / n, judge(fitted).ece,
                judge(key).ece, accepted,
                accepted ? 100.0 * acceptedTouching / accepted : 0.0);
  }
}

int run(const Options& o) {
  std::vector<CaseResult> results;
  for (const Case& c : casesOf(o)) results.push_back(collect(c, o.rotations));
  if (!o.samplesPath.empty()) writeSamples(o.samplesPath, results);
  std::vector<CaseSamples> fitBudget, fitQuality;
  for (const CaseResult& c : results) {
    if (!c.fit) continue;
    fitBudget.push_back(c.budget);
    fitQuality.push_back(c.quality);
  }
  const std::vector<bool> evidence(adb::kEvidenceFeature.begin(), adb::kEvidenceFeature.end());
  const adb::calibrate::Weights budget = adb::calibrate::fitLogistic(fitBudget, evidence);
  Estimate fresh;
  fresh.budget = toArray<adb::kEstimateFeatures>(budget);
  fresh.map = adb::calibrate::fitMonotone(fitBudget, budget, o.knots);
  fresh.quality = toArray<adb::kEstimateFeatures>(adb::calibrate::fitLogistic(
      fitQuality, std::vector<bool>(adb::kEstimateFeatures, false)));
  printWeights("kBudgetWeights", fresh.budget);
  printMap(fresh.map);
  printWeights("kQualityWeights", fresh.quality);
  // The open-pair estimate: a plain logistic model of whether an open pair's triangles meet.
  std::vector<CaseSamples> fitPairs;
  for (const CaseResult& c : results) {
    if (c.fit) fitPairs.push_back(c.openPairs);
  }
  const adb::OpenPairWeights pairWeights = toArray<adb::kOpenPairFeatures>(
      adb::calibrate::fitLogistic(fitPairs, std::vector<bool>(adb::kOpenPairFeatures, false)));
  std::printf("constexpr OpenPairWeights kOpenPairWeights{");
  for (int i = 0; i < adb::kOpenPairFeatures; ++i) {
    std::printf("%s%.6g", i ? ", " : "", pairWeights[i]);
  }
  std::printf("};\n");
  printCheckTable("At QuerySettings' defaults, as the library answers (its compiled estimate):",
                  results, nullptr);
  printCheckTable("The same queries with the weights and map just fitted:", results, &fresh);
  printQuality(results, fresh.quality);
  printOpenPairs(results, pairWeights);
  std::filesystem::create_directories(o.outDir);
  const std::string csv = o.outDir + "/reliability.csv";
  writeReliability(csv, results);
  std::printf("\nreliability diagrams: %s", csv.c_str());
  if (o.plots && adb::tradeoff::runPythonScript(ADB_CALIBRATE_PLOT_SCRIPT, o.outDir,
                                                "adb-calibrate")) {
    std::printf(", %s/reliability.png", o.outDir.c_str());
  }
  std::printf("\n");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"", "adb-calibrate"};
  Options o;
  addOptions(app, o);
  if (const std::optional<int> exitCode =
          adb::tools::parseCommandLine(app, "adb-calibrate", argc, argv)) {
    return *exitCode;
  }
  try {
    return run(o);
  } catch (const std::exception& e) {  // a mesh file assimp cannot read, or bad geometry
    std::fprintf(stderr, "adb-calibrate: error: %s\n", e.what());
    return 1;
  }
}
