// queries.csv: one row per query and method, with the poses at full precision so that anyone
// can re-check every answer with another library (format: docs/benchmark.md).
// Rows are written as they are measured and flushed after each model, so the rows of
// finished models survive a later failure.
#pragma once

#include <cstddef>
#include <fstream>
#include <string>

#include "method.h"
#include "results.h"
#include "study_poses.h"

namespace adb::tradeoff {

/// The header line, exactly.
extern const char* const kQueryCsvHeader;

class QueryCsv {
 public:
  /// Creates (truncates) `path` and writes the header. Throws std::runtime_error on failure.
  explicit QueryCsv(const std::string& path);

  void write(const std::string& model, std::size_t triangles, const std::string& method,
             const MethodParams& params, double distance, int rotation, const StudyPose& pose,
             const QueryRecord& record);
  /// Flushes to disk; throws std::runtime_error when the stream failed.
  void flush();

 private:
  std::string m_path;
  std::ofstream m_out;
};

}  // namespace adb::tradeoff
