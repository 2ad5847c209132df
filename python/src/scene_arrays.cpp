#include "scene_arrays.h"

namespace adb::python {

py::dict stepArrays(const std::vector<double>& rows) {
  const std::size_t steps = rows.size() / scene::kStepColumns;
  const auto cells = scene::stepCells(scene::StepRecord{});
  py::dict d;
  for (std::size_t c = 0; c < cells.size(); ++c) {
    if (cells[c].integer) {
      py::array_t<std::int64_t> a = newArray<std::int64_t>({static_cast<py::ssize_t>(steps)});
      for (std::size_t i = 0; i < steps; ++i) {
        a.mutable_at(static_cast<py::ssize_t>(i)) =
            static_cast<std::int64_t>(rows[i * scene::kStepColumns + c]);
      }
      d[cells[c].column] = a;
    } else {
      py::array_t<double> a = newArray<double>({static_cast<py::ssize_t>(steps)});
      for (std::size_t i = 0; i < steps; ++i) {
        a.mutable_at(static_cast<py::ssize_t>(i)) = rows[i * scene::kStepColumns + c];
      }
      d[cells[c].column] = a;
    }
  }
  return d;
}

py::dict contactArrays(const std::vector<scene::ContactPoint>& points) {
  const auto n = static_cast<py::ssize_t>(points.size());
  py::array_t<double> position = newArray<double>({n, 3});
  py::array_t<double> depth = newArray<double>({n});
  py::array_t<double> confidence = newArray<double>({n});
  py::array_t<std::int64_t> bodies = newArray<std::int64_t>({n, 2});
  for (py::ssize_t i = 0; i < n; ++i) {
    const scene::ContactPoint& p = points[static_cast<std::size_t>(i)];
    for (int k = 0; k < 3; ++k) position.mutable_at(i, k) = p.position[k];
    depth.mutable_at(i) = p.depth;
    confidence.mutable_at(i) = p.confidence;
    bodies.mutable_at(i, 0) = p.body0;
    bodies.mutable_at(i, 1) = p.body1;
  }
  py::dict d;
  d["position"] = position;
  d["depth"] = depth;
  d["confidence"] = confidence;
  d["bodies"] = bodies;
  return d;
}

py::dict eventArrays(const std::vector<scene::OverlapEvent>& events) {
  const auto n = static_cast<py::ssize_t>(events.size());
  py::array_t<std::int64_t> step = newArray<std::int64_t>({n});
  py::array_t<double> time = newArray<double>({n});
  py::array_t<bool> begin = newArray<bool>({n});
  py::dict d = pairArrays(events);
  for (py::ssize_t i = 0; i < n; ++i) {
    const scene::OverlapEvent& e = events[static_cast<std::size_t>(i)];
    step.mutable_at(i) = e.step;
    time.mutable_at(i) = e.time;
    begin.mutable_at(i) = e.begin;
  }
  d["step"] = step;
  d["time"] = time;
  d["begin"] = begin;
  return d;
}

py::dict summaryDict(const scene::RunSummary& s) {
  py::dict d;
  d["backend"] = s.backend;
  d["effects"] = s.effects;
  d["world"] = s.world;
  d["steps"] = s.steps;
  d["bodies"] = s.bodies;
  d["triangles"] = s.triangles;
  d["build_seconds"] = s.buildSeconds;
  d["mean_step_ms"] = s.meanStepMillis;
  d["p99_step_ms"] = s.p99StepMillis;
  d["max_step_ms"] = s.maxStepMillis;
  d["mean_pair_ms"] = s.meanPairMillis;
  d["mean_budget_use"] = s.meanBudgetUse;
  d["mean_confidence"] = s.meanConfidence;
  d["worst_confidence"] = s.worstConfidence;
  d["max_penetration"] = s.maxPenetration;
  d["most_lost"] = s.mostLost;
  d["lost_at_end"] = s.lostAtEnd;
  d["at_rest_at_end"] = s.atRestAtEnd;
  d["asleep_at_end"] = s.asleepAtEnd;
  d["all_asleep_from"] = s.allAsleepFrom;
  d["dynamic_bodies"] = s.dynamicBodies;
  return d;
}

}  // namespace adb::python
