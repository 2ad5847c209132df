#include "pile/pile_run.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace adb::demo {
namespace {

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
         "floor_penetration,floor_penetration_relative,lost,probed_depth,probed_relative,probed_mean,needed_node_pairs,mean_completeness,worst_completeness,other_node_pairs,from_scratch_node_pairs\n";
}

void writeCsvRow(std::ofstream& csv, int step, const StepStats& s) {
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
      << ',' << f.otherNodePairs << ',' << f.fromScratchNodePairs << '\n';
}

struct Totals {
  std::vector<double> stepSeconds, frameMicros;
  double worstPenetration = 0, lowest = 1e300, confidenceSum = 0, worstConfidence = 1;
  double worstBody = 0, worstBin = 0, worstFloor = 0, worstFloorRelative = 0;
  double worstProbed = -1, worstProbedRelative = -1, probedMeanSum = 0;
  int probes = 0;
  int mostLost = 0;
  std::uint64_t pairs = 0, cutPairs = 0, exactContacts = 0, plausibleContacts = 0;

  void add(const StepStats& s) {
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

int runPile(const PileRunOptions& o) {
  const bool adbBackend = o.settings.backend == Backend::Adb;
  const char* backend = adbBackend                                        ? "adb"
                        : o.settings.backend == Backend::GImpact ? "GImpact"
                                                                         : "convex (HACD)";
  std::unique_ptr<PileScene> made;
  try {
    made = std::make_unique<PileScene>(o.settings);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "adb-demo: %s\n", e.what());
    return 2;
  }
  PileScene& scene = *made;
  const char* floors[] = {"box meshes", "btBoxShape floor and walls",
                          "btStaticPlaneShape floor, btBoxShape walls"};
  std::printf("pile scene: %d bodies, %zu triangles in all, backend %s, %d steps of 1/60 s\n"
              "bin: %s\n",
              scene.bodyCount(), scene.triangleCount(), backend, o.steps,
              floors[static_cast<int>(o.settings.floor)]);
  if (o.settings.backend == Backend::Convex) {
    const DecompositionReport& d = scene.decomposition();
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
    const adb::FrameSettings& f = o.settings.frame;
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
  StepStats last;
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

}  // namespace adb::demo
