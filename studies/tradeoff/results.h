// What one model's run produced, kept in memory for the summary: per method, one record per
// pose (same order for every method), plus the pose facts the summary needs.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "adb/core/cell_histogram.h"
#include "method.h"

namespace adb::tradeoff {

struct QueryRecord {
  double timeNs = 0.0;
  bool collides = false;
  double confidence = 1.0;
  std::int64_t nodePairs = -1;  ///< -1: the method cannot tell
};

struct MethodRecords {
  std::string name;
  MethodParams params;
  std::vector<QueryRecord> queries;  ///< indexed like ModelResult::distance
};

/// One case's results: a model against a copy of itself, or a pair ("A+B", triangles A's
/// plus B's).
struct ModelResult {
  std::string label;
  std::size_t triangles = 0;
  std::string note;  ///< the models, their triangles and aspects, the unit (summary.md)
  std::vector<double> distance;     ///< per pose
  std::vector<bool> rootsOverlap;   ///< per pose
  std::vector<MethodRecords> methods;
  CellHistogram cells;
};

}  // namespace adb::tradeoff
