// A scene world's records as numpy arrays and dicts: the steps (the columns of steps.csv),
// contact points, pairs with a confidence (cut, overlapping), overlap events and the summary.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <vector>

#include "adb/scene/recorder.h"
#include "adb/scene/scene_world.h"
#include "arrays.h"

namespace adb::python {

namespace py = pybind11;

/// Rows of scene::kStepColumns values, one per step, as a dict of column arrays (int64 for
/// counts, float64 otherwise), named and ordered as steps.csv.
py::dict stepArrays(const std::vector<double>& rows);
/// 'position' (N, 3), 'depth', 'confidence' and 'bodies' (N, 2).
py::dict contactArrays(const std::vector<scene::ContactPoint>& points);
/// 'step', 'time', 'begin', 'bodies' (N, 2) and 'confidence'.
py::dict eventArrays(const std::vector<scene::OverlapEvent>& events);
/// The summary's figures by name (summary.json's).
py::dict summaryDict(const scene::RunSummary& summary);

/// 'bodies' (N, 2) and 'confidence' of any pair record with body0, body1 and confidence.
template <class Pair>
py::dict pairArrays(const std::vector<Pair>& pairs) {
  const auto n = static_cast<py::ssize_t>(pairs.size());
  py::array_t<std::int64_t> bodies = newArray<std::int64_t>({n, 2});
  py::array_t<double> confidence = newArray<double>({n});
  for (py::ssize_t i = 0; i < n; ++i) {
    bodies.mutable_at(i, 0) = pairs[static_cast<std::size_t>(i)].body0;
    bodies.mutable_at(i, 1) = pairs[static_cast<std::size_t>(i)].body1;
    confidence.mutable_at(i) = pairs[static_cast<std::size_t>(i)].confidence;
  }
  py::dict d;
  d["bodies"] = bodies;
  d["confidence"] = confidence;
  return d;
}

}  // namespace adb::python
