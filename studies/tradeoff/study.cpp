// The measurement loop of one case.
#include "study.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "adb/support/benchmark_poses.h"
#include "adb/support/mesh_generators.h"
#include "root_overlap.h"
#include "study_poses.h"
#include "timing.h"

namespace adb::tradeoff {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void prepareAll(const Model& a, const Model& b, StudyContext& context) {
  // Build times per method name, in first-seen order (ADB settings and the exact mode share
  // one tree per model: the first of them builds it, the others take no time).
  std::vector<std::pair<std::string, double>> seconds;
  for (auto& method : context.methods) {
    const auto start = std::chrono::steady_clock::now();
    method->prepare(a, b);
    const double s = secondsSince(start);
    auto it = std::find_if(seconds.begin(), seconds.end(),
                           [&](const auto& e) { return e.first == method->name(); });
    if (it == seconds.end()) {
      seconds.emplace_back(method->name(), s);
    } else {
      it->second += s;
    }
  }
  std::string line = caseLabel(a, b) + " (" + std::to_string(a.mesh.triangleCount());
  if (&a != &b) line += " + " + std::to_string(b.mesh.triangleCount());
  line += " triangles) prepared in";
  for (const auto& [name, s] : seconds) {
    char buf[64];
    std::snprintf(buf, sizeof buf, " %s %.2f s", name.c_str(), s);
    line += buf;
  }
  context.progress.note(line);
}

QueryRecord toRecord(const TimedAnswer& t) {
  return QueryRecord{t.nanoseconds, t.answer.collides, t.answer.confidence, t.answer.nodePairs};
}

// One model's part of the notes: name, triangles and median aspect.
std::string modelNote(const Model& m) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "%s (%zu triangles, median aspect %.1f, unit %.4g)",
                m.label.c_str(), m.mesh.triangleCount(), adb::gen::medianAspect(m.mesh),
                benchmarkUnit(m.mesh.bounds()));
  return buf;
}

std::string caseNote(const Model& a, const Model& b) {
  if (&a == &b) return "Model " + modelNote(a) + ".";
  char unit[64];
  std::snprintf(unit, sizeof unit, "%.4g", benchmarkUnit(a.mesh.bounds(), b.mesh.bounds()));
  return "Pair " + caseLabel(a, b) + ": " + modelNote(a) + " against " + modelNote(b) +
         "; distances in the pair's unit, " + unit + " (the mean of the two).";
}

// Every method answers one pose; the rows go to queries.csv and the records to `result`.
void measurePose(const StudyPose& pose, double distance, int rotation, const Aabb& boundsA,
                 const Aabb& boundsB, ModelResult& result, StudyContext& context) {
  const Options& o = context.options;
  result.distance.push_back(distance);
  result.rootsOverlap.push_back(rootBoxesOverlap(boundsA, pose.a.pose, boundsB, pose.b.pose));
  for (std::size_t m = 0; m < context.methods.size(); ++m) {
    Method& method = *context.methods[m];
    const QueryRecord record =
        toRecord(timeQuery(method, pose.a.pose, pose.b.pose, o.repeats, o.warmup));
    result.methods[m].queries.push_back(record);
    context.csv.write(result.label, result.triangles, method.name(), method.params(), distance,
                      rotation, pose, record);
    context.progress.advance();
  }
}

}  // namespace

std::string caseLabel(const Model& a, const Model& b) {
  return &a == &b ? a.label : a.label + "+" + b.label;
}

std::uint64_t queriesPerCase(const Options& options, std::size_t methodCount) {
  const std::uint64_t poses =
      options.poses == PoseMode::Inside ? 1 : static_cast<std::uint64_t>(options.distances.size());
  return poses * static_cast<std::uint64_t>(options.rotations) * methodCount;
}

ModelResult runCase(const Model& a, const Model& b, std::size_t caseIndex,
                    StudyContext& context) {
  const Options& o = context.options;
  prepareAll(a, b, context);
  ModelResult result;
  result.label = caseLabel(a, b);
  // A pair's rows count both models' triangles (docs/benchmark.md).
  result.triangles = a.mesh.triangleCount() + (&a == &b ? 0 : b.mesh.triangleCount());
  result.note = caseNote(a, b);
  for (const auto& method : context.methods) {
    result.methods.push_back(MethodRecords{method->name(), method->params(), {}});
  }
  const Aabb& boundsA = a.mesh.bounds();
  const Aabb& boundsB = b.mesh.bounds();
  if (o.poses == PoseMode::Inside) {
    const std::vector<StudyPose> poses =
        insideStudyPoses(boundsA, boundsB, o.rotations, o.seed, caseIndex);
    for (int r = 0; r < o.rotations; ++r) {
      const StudyPose& pose = poses[static_cast<std::size_t>(r)];
      measurePose(pose, measuredDistance(pose, boundsA, boundsB), r, boundsA, boundsB, result,
                  context);
    }
  } else {
    for (std::size_t d = 0; d < o.distances.size(); ++d) {
      const std::vector<StudyPose> poses =
          studyPoses(boundsA, boundsB, o.distances[d], o.rotations, o.seed, caseIndex, d);
      for (int r = 0; r < o.rotations; ++r) {
        measurePose(poses[static_cast<std::size_t>(r)], o.distances[d], r, boundsA, boundsB,
                    result, context);
      }
    }
  }
  context.csv.flush();
  return result;
}

}  // namespace adb::tradeoff
