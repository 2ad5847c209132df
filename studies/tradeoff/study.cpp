// The measurement loop of one model.
#include "study.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "root_overlap.h"
#include "study_poses.h"
#include "timing.h"

namespace adb::tradeoff {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void prepareAll(const Model& model, StudyContext& context) {
  // Build times per method name, in first-seen order (ADB settings and the exact mode share
  // one tree: the first of them builds it, the others take no time).
  std::vector<std::pair<std::string, double>> seconds;
  for (auto& method : context.methods) {
    const auto start = std::chrono::steady_clock::now();
    method->prepare(model);
    const double s = secondsSince(start);
    auto it = std::find_if(seconds.begin(), seconds.end(),
                           [&](const auto& e) { return e.first == method->name(); });
    if (it == seconds.end()) {
      seconds.emplace_back(method->name(), s);
    } else {
      it->second += s;
    }
  }
  std::string line = model.label + " (" + std::to_string(model.mesh.triangleCount()) +
                     " triangles) prepared in";
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

}  // namespace

std::uint64_t queriesPerModel(const Options& options, std::size_t methodCount) {
  return static_cast<std::uint64_t>(options.distances.size()) *
         static_cast<std::uint64_t>(options.rotations) * methodCount;
}

ModelResult runModel(const Model& model, StudyContext& context) {
  const Options& o = context.options;
  prepareAll(model, context);
  ModelResult result;
  result.label = model.label;
  result.triangles = model.mesh.triangleCount();
  for (const auto& method : context.methods) {
    result.methods.push_back(MethodRecords{method->name(), method->params(), {}});
  }
  for (std::size_t d = 0; d < o.distances.size(); ++d) {
    const double distance = o.distances[d];
    const std::vector<StudyPose> poses =
        studyPoses(model.mesh.bounds(), distance, o.rotations, o.seed, model.index, d);
    for (int r = 0; r < o.rotations; ++r) {
      const StudyPose& pose = poses[static_cast<std::size_t>(r)];
      result.distance.push_back(distance);
      result.rootsOverlap.push_back(rootBoxesOverlap(model.mesh.bounds(), pose.a.pose, pose.b.pose));
      for (std::size_t m = 0; m < context.methods.size(); ++m) {
        Method& method = *context.methods[m];
        const QueryRecord record =
            toRecord(timeQuery(method, pose.a.pose, pose.b.pose, o.repeats, o.warmup));
        result.methods[m].queries.push_back(record);
        context.csv.write(result.label, result.triangles, method.name(), method.params(), distance,
                          r, pose, record);
        context.progress.advance();
      }
    }
  }
  context.csv.flush();
  return result;
}

}  // namespace adb::tradeoff
