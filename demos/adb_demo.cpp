// adb-demo: runs the pile scene headless (generated tori, gears and torus knots, or copies of
// mesh files, dropped into a bin) with adb's MeshShape, with Bullet's GImpact, or with a convex
// decomposition (Bullet's HACD) of the same meshes, prints a line every N steps and a final
// table, and writes the per-step figures as CSV with --out.
//
//   build/bin/adb-demo [--backend adb|gimpact|convex] [--bodies N] [--triangles N] [--steps N]
//                      [--every N] [--seed S] [--out DIR] [--floor mesh|box|plane]
//                      [--mesh FILE]...
//                      [--budget-us US] [--budget-pairs N] [--p-min P] [--k-min K]
//                      [--p-accept P] [--no-soften]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "adb/io/mesh_file.h"
#include "scene/pile_scene.h"

namespace {

struct Options {
  adb::demo::SceneSettings scene;
  int steps = 300;
  int every = 30;
  int probeEvery = 0;  // measure body-body penetration from the geometry every N steps
  std::string out;
};

[[noreturn]] void usage(int code) {
  std::fprintf(code ? stderr : stdout,
               "usage: adb-demo [--backend adb|gimpact|convex] [--bodies N] [--triangles N] "
               "[--steps N] [--every N] [--seed S] [--out DIR]\n"
               "                [--floor mesh|box|plane] [--mesh FILE]...\n"
               "                [--budget-us US] [--budget-pairs N] [--p-min P] [--k-min K] "
               "[--p-accept P] [--no-soften]\n"
               "  --backend       adb's MeshShape (default), Bullet's GImpact, or each mesh "
               "decomposed into\n"
               "                  convex hulls by Bullet's HACD (btCompoundShape of "
               "btConvexHullShape)\n"
               "  --floor         the bin: box meshes (default), btBoxShape floor and walls, or a "
               "btStaticPlaneShape\n"
               "                  floor between btBoxShape walls; the same for every backend\n"
               "  --mesh          bodies are copies of this mesh file (any format assimp reads), "
               "scaled to 0.8\n"
               "                  across; repeat to cycle through several (default: generated "
               "tori, gears, knots)\n"
               "  --budget-us     wall-clock budget per step for all mesh-mesh pairs (default "
               "none)\n"
               "  --budget-pairs  node pairs per step for all mesh-mesh pairs: reproducible\n"
               "  --p-min/--k-min stop refining a pair at k_min node pairs above p_min "
               "(default k_min 0: never)\n"
               "  --p-accept      unresolved node pairs at or above this become plausible "
               "contacts (0.9)\n"
               "  --no-soften     plausible contacts push as hard as exact ones\n"
               "  --probe-every N measure body-body penetration from the geometry every N "
               "steps (untimed;\n"
               "                  the same measure for every backend; default 0: off)\n");
  std::exit(code);
}

// A number that must be all of `value`: "12x" is an error, not 12.
double number(const std::string& flag, const std::string& value) {
  char* end = nullptr;
  const double v = std::strtod(value.c_str(), &end);
  if (value.empty() || *end != '\0' || std::isnan(v)) {
    std::fprintf(stderr, "adb-demo: %s needs a number, got '%s'\n", flag.c_str(), value.c_str());
    std::exit(2);
  }
  return v;
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help") usage(0);
    if (arg == "--no-soften") {
      o.scene.frame.softenPlausible = false;
      continue;
    }
    if (i + 1 >= argc) usage(2);
    const std::string value = argv[++i];
    if (arg == "--backend" && (value == "adb" || value == "gimpact" || value == "convex")) {
      o.scene.backend = value == "adb"       ? adb::demo::Backend::Adb
                        : value == "gimpact" ? adb::demo::Backend::GImpact
                                             : adb::demo::Backend::Convex;
    } else if (arg == "--bodies") {
      o.scene.bodies = std::max(1, std::atoi(value.c_str()));
    } else if (arg == "--triangles") {
      o.scene.trianglesPerBody = std::strtoull(value.c_str(), nullptr, 10);
    } else if (arg == "--steps") {
      o.steps = std::max(1, std::atoi(value.c_str()));
    } else if (arg == "--every") {
      o.every = std::max(1, std::atoi(value.c_str()));
    } else if (arg == "--seed") {
      o.scene.seed = std::strtoull(value.c_str(), nullptr, 10);
    } else if (arg == "--floor" && (value == "mesh" || value == "box" || value == "plane")) {
      o.scene.floor = value == "mesh"  ? adb::demo::Floor::Mesh
                      : value == "box" ? adb::demo::Floor::Box
                                       : adb::demo::Floor::Plane;
    } else if (arg == "--mesh") {
      try {
        o.scene.meshes.push_back(adb::io::loadMesh(value));
      } catch (const std::exception& e) {
        std::fprintf(stderr, "adb-demo: %s\n", e.what());
        std::exit(2);
      }
    } else if (arg == "--probe-every") {
      o.probeEvery = std::max(0, std::atoi(value.c_str()));
    } else if (arg == "--out") {
      o.out = value;
    } else if (arg == "--budget-us") {
      o.scene.frame.budgetMicros = number(arg, value);
    } else if (arg == "--budget-pairs") {
      o.scene.frame.budgetNodePairs = static_cast<std::uint64_t>(std::max(0.0, number(arg, value)));
    } else if (arg == "--p-min") {
      o.scene.frame.pMin = number(arg, value);
    } else if (arg == "--k-min") {
      o.scene.frame.kMin = static_cast<int>(number(arg, value));
    } else if (arg == "--p-accept") {
      o.scene.frame.pAccept = number(arg, value);
    } else {
      std::fprintf(stderr, "adb-demo: bad flag or value: %s %s\n", arg.c_str(), value.c_str());
      usage(2);
    }
  }
  return o;
}

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(q * static_cast<double>(v.size() - 1))];
}

std::string budgetText(const adb::FrameSettings& f) {
  std::string text;
  if (std::isfinite(f.budgetMicros)) text += std::to_string(static_cast<long>(f.budgetMicros)) + " us";
  if (f.budgetNodePairs != adb::FrameSettings{}.budgetNodePairs) {
    text += (text.empty() ? "" : " and ") + std::to_string(f.budgetNodePairs) + " node pairs";
  }
  return text.empty() ? "none" : text + " per step";
}

void writeCsvHeader(std::ofstream& csv) {
  csv << "step,seconds,contacts,max_penetration,kinetic,energy,at_rest,lowest_y,"
         "frame_us,contact_us,pairs,exact_pairs,quality_pairs,cut_pairs,node_pairs,exact_contacts,"
         "plausible_contacts,mean_confidence,worst_confidence,body_penetration,bin_penetration,"
         "floor_penetration,floor_penetration_relative,lost,probed_depth,probed_relative,probed_mean,needed_node_pairs,mean_completeness,worst_completeness,other_node_pairs\n";
}

void writeCsvRow(std::ofstream& csv, int step, const adb::demo::StepStats& s) {
  const adb::FrameStats& f = s.frame;
  csv << step << ',' << s.seconds << ',' << s.contacts << ',' << s.maxPenetration << ','
      << s.kinetic << ',' << s.energy << ',' << s.atRest << ',' << s.lowestY << ',' << f.micros
      << ',' << f.contactMicros << ',' << f.pairs << ',' << f.exactPairs << ',' << f.qualityPairs << ',' << f.cutPairs
      << ',' << f.nodePairs << ',' << f.exactContacts << ',' << f.plausibleContacts << ','
      << f.meanConfidence << ',' << f.worstConfidence << ',' << s.bodyPenetration << ','
      << s.binPenetration << ',' << s.floorPenetration << ',' << s.floorPenetrationRelative
      << ',' << s.lost << ',';
  if (s.probedDepth >= 0) {
    csv << s.probedDepth << ',' << s.probedRelative << ',' << s.probedMean;
  } else {
    csv << ",,";
  }
  csv << ',' << f.neededNodePairs << ',' << f.meanCompleteness << ',' << f.worstCompleteness
      << ',' << f.otherNodePairs << '\n';
}

struct Totals {
  std::vector<double> stepSeconds, frameMicros;
  double worstPenetration = 0, lowest = 1e300, confidenceSum = 0, worstConfidence = 1;
  double worstBody = 0, worstBin = 0, worstFloor = 0, worstFloorRelative = 0;
  double worstProbed = -1, worstProbedRelative = -1, probedMeanSum = 0;
  int probes = 0;
  int mostLost = 0;
  std::uint64_t pairs = 0, cutPairs = 0, exactContacts = 0, plausibleContacts = 0;

  void add(const adb::demo::StepStats& s) {
    stepSeconds.push_back(s.seconds);
    frameMicros.push_back(s.frame.micros);
    worstPenetration = std::max(worstPenetration, s.maxPenetration);
    lowest = std::min(lowest, s.lowestY);
    worstBody = std::max(worstBody, s.bodyPenetration);
    worstBin = std::max(worstBin, s.binPenetration);
    worstFloor = std::max(worstFloor, s.floorPenetration);
    worstFloorRelative = std::max(worstFloorRelative, s.floorPenetrationRelative);
    worstProbed = std::max(worstProbed, s.probedDepth);
    worstProbedRelative = std::max(worstProbedRelative, s.probedRelative);
    mostLost = std::max(mostLost, s.lost);
    if (s.probedMean >= 0) {
      probedMeanSum += s.probedMean;
      ++probes;
    }
    confidenceSum += s.frame.meanConfidence;
    worstConfidence = std::min(worstConfidence, s.frame.worstConfidence);
    pairs += s.frame.pairs;
    cutPairs += s.frame.cutPairs;
    exactContacts += s.frame.exactContacts;
    plausibleContacts += s.frame.plausibleContacts;
  }
};

double mean(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v) sum += x;
  return v.empty() ? 0.0 : sum / static_cast<double>(v.size());
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  const bool adbBackend = o.scene.backend == adb::demo::Backend::Adb;
  const char* backend = adbBackend                                        ? "adb"
                        : o.scene.backend == adb::demo::Backend::GImpact ? "GImpact"
                                                                         : "convex (HACD)";
  std::unique_ptr<adb::demo::PileScene> made;
  try {
    made = std::make_unique<adb::demo::PileScene>(o.scene);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "adb-demo: %s\n", e.what());
    return 2;
  }
  adb::demo::PileScene& scene = *made;
  const char* floors[] = {"box meshes", "btBoxShape floor and walls",
                          "btStaticPlaneShape floor, btBoxShape walls"};
  std::printf("pile scene: %d bodies, %zu triangles in all, backend %s, %d steps of 1/60 s\n"
              "bin: %s\n",
              scene.bodyCount(), scene.triangleCount(), backend, o.steps,
              floors[static_cast<int>(o.scene.floor)]);
  if (o.scene.backend == adb::demo::Backend::Convex) {
    const adb::demo::DecompositionReport& d = scene.decomposition();
    std::string perKind, volumes;
    for (std::size_t k = 0; k < d.hullsPerKind.size(); ++k) {
      char ratio[32];
      std::snprintf(ratio, sizeof ratio, d.volumeRatio[k] > 0 ? "%.2f" : "n/a",
                    d.volumeRatio[k]);
      perKind += (k ? ", " : "") + std::to_string(d.hullsPerKind[k]);
      volumes += (k ? ", " : "") + std::string(ratio);
    }
    std::printf("convex decomposition (HACD): %zu hulls over %zu meshes (%s), prepared in %.2f s;"
                " hulls' volume / mesh volume: %s\n",
                d.hulls, d.hullsPerKind.size(), perKind.c_str(), d.seconds, volumes.c_str());
  }
  if (adbBackend) {
    const adb::FrameSettings& f = o.scene.frame;
    std::printf("budget %s, p_min %.3g, k_min %d%s, p_accept %.3g%s\n", budgetText(f).c_str(),
                f.pMin, f.kMin, f.kMin == 0 ? " (never stop on quality)" : "", f.pAccept,
                f.softenPlausible ? ", plausible contacts softened" : "");
  }
  std::printf("\n%6s %9s %9s %8s %6s %5s %9s %10s %10s %9s %8s\n", "step", "ms/step",
              "pairs us", "contacts", "pairs", "cut", "conf.", "max pen.", "floor pen.", "energy",
              "at rest");

  std::ofstream csv;
  if (!o.out.empty()) {
    std::filesystem::create_directories(o.out);
    csv.open(o.out + "/steps.csv");
    writeCsvHeader(csv);
  }
  Totals totals;
  adb::demo::StepStats last;
  for (int step = 1; step <= o.steps; ++step) {
    last = scene.step();
    if (o.probeEvery > 0 && (step % o.probeEvery == 0 || step == o.steps)) scene.probe(last);
    totals.add(last);
    if (csv) writeCsvRow(csv, step, last);
    if (step % o.every == 0 || step == o.steps) {
      std::printf("%6d %9.3f %9.0f %8d %6u %5u %9.4f %10.4f %10.4f %9.3f %5d/%d\n", step,
                  last.seconds * 1e3, last.frame.micros, last.contacts, last.frame.pairs,
                  last.frame.cutPairs, last.frame.meanConfidence, last.maxPenetration,
                  last.floorPenetration, last.energy, last.atRest, scene.bodyCount());
      std::fflush(stdout);
    }
  }
  std::printf("\n| backend | steps | mean ms/step | p99 ms/step | mesh pairs: mean us | p99 us | "
              "pairs cut | contacts exact/plausible | mean conf. | worst conf. | "
              "max penetration | lowest centre | energy (last) | at rest (last) |\n"
              "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
  std::printf("| %s | %d | %.3f | %.3f | %.0f | %.0f | %llu/%llu | %llu/%llu | %.4f | %.4f | "
              "%.4f | %.3f | %.3f | %d/%d |\n",
              backend, o.steps, mean(totals.stepSeconds) * 1e3,
              percentile(totals.stepSeconds, 0.99) * 1e3, mean(totals.frameMicros),
              percentile(totals.frameMicros, 0.99),
              static_cast<unsigned long long>(totals.cutPairs),
              static_cast<unsigned long long>(totals.pairs),
              static_cast<unsigned long long>(totals.exactContacts),
              static_cast<unsigned long long>(totals.plausibleContacts),
              totals.confidenceSum / static_cast<double>(o.steps), totals.worstConfidence,
              totals.worstPenetration, totals.lowest, last.energy, last.atRest,
              scene.bodyCount());
  // Penetrations apart: contacts between bodies, contacts with the bin, and the floor's
  // by geometry (lowest vertex below y = 0; relative: over the body's bounding-box diagonal).
  std::printf("\n| max pen. body-body | max pen. body-bin | floor pen. max | floor pen. max "
              "/ body size | floor pen. (last) | floor pen. (last) / body size |\n"
              "|---|---|---|---|---|---|\n"
              "| %.4f | %.4f | %.4f | %.2f %% | %.4f | %.2f %% |\n",
              totals.worstBody, totals.worstBin, totals.worstFloor,
              totals.worstFloorRelative * 100, last.floorPenetration,
              last.floorPenetrationRelative * 100);
  std::printf("\nbodies lost (centre out of the bin): %d at most, %d at the end\n",
              totals.mostLost, last.lost);
  if (totals.worstProbed >= 0) {
    std::printf("body-body penetration from the geometry (every %d steps): max %.4f "
                "(%.2f %% of a body's size), at the end %.4f (%.2f %%); each body's deepest, "
                "mean over bodies and probes %.4f\n",
                o.probeEvery, totals.worstProbed, totals.worstProbedRelative * 100,
                last.probedDepth, last.probedRelative * 100,
                totals.probedMeanSum / std::max(1, totals.probes));
  }
  if (csv) std::printf("\nper-step figures: %s/steps.csv\n", o.out.c_str());
  // Below the floor (y = 0) by more than a body means one fell through: say so in the exit.
  return totals.lowest < -0.5 ? 1 : 0;
}
