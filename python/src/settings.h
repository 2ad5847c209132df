// Keyword arguments as the layers' settings, checked in one place: the query keywords of
// adb.collide, adb.collide_many and adb.CollisionManager as the core's QuerySettings, and the
// range check every other setting (tree, scene, world) goes through.
#pragma once

#include <pybind11/pybind11.h>

#include <optional>
#include <string>

#include "adb/core/query.h"

namespace adb::python {

namespace py = pybind11;

struct QueryOptions {
  std::string mode = "adb";              ///< "adb" or "exact"
  double pMin = 0.99;
  long long kMin = 10;
  std::optional<double> budgetUs;        ///< None: no time budget
  std::optional<long long> budgetPairs;  ///< None: no node-pair budget
  std::optional<bool> stopAtFirstHit;    ///< None: true (a yes/no answer)
  long long maxWitnesses = 64;
  double contactMargin = 0.0;
};

/// The settings, validated: SettingsError names the first bad keyword and its range.
QuerySettings querySettings(const QueryOptions& options);

/// Throws SettingsError "name: value, expected lo to hi" unless lo <= value <= hi (NaN fails).
void requireRange(double value, double lo, double hi, const char* name);

/// The keyword arguments, with their defaults, in the order the functions take them.
#define ADB_QUERY_KWARGS                                                                    \
  py::kw_only(), py::arg("mode") = "adb", py::arg("p_min") = 0.99, py::arg("k_min") = 10,   \
      py::arg("budget_us") = py::none(), py::arg("budget_pairs") = py::none(),              \
      py::arg("stop_at_first_hit") = py::none(), py::arg("max_witnesses") = 64,             \
      py::arg("contact_margin") = 0.0

}  // namespace adb::python
