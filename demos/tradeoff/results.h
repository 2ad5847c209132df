// What one model's run produced, kept in memory for the summary: per method, one record per
// pose (same order for every method), plus the pose facts the summary needs.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

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

/// The paper's Fig. 8: per cell index (x + 8y + 64z of an 8^3 grid over a node's box), the
/// number of nodes for which that cell is a possible collision cell.
struct CellHistogram {
  std::array<std::uint64_t, 512> count{};
  std::size_t nodesCounted = 0;
  std::size_t nodesTotal = 0;
  std::size_t stride = 1;  ///< 1: every node; s > 1: every s-th node per level, counts scaled
  double seconds = 0.0;
};

struct ModelResult {
  std::string label;
  std::size_t triangles = 0;
  std::vector<double> distance;     ///< per pose
  std::vector<bool> rootsOverlap;   ///< per pose
  std::vector<MethodRecords> methods;
  CellHistogram cells;
};

}  // namespace adb::tradeoff
