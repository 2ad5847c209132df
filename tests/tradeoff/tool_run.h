// Test helpers for adb-tradeoff: run the built executable with arguments (exit status and
// stderr captured), a fresh scratch directory per test, and a small CSV reader.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace adb::tradeoff::test {

struct RunResult {
  int exitCode = -1;
  std::string stderrText;
};

/// Runs adb-tradeoff (path compiled in) with `args`; stdout is discarded.
RunResult runTool(const std::vector<std::string>& args);

/// An empty directory for the calling test, under the build tree.
std::string freshDir(const std::string& name);

/// A CSV file: its header fields and rows (fields split on commas; our tests never quote).
struct CsvTable {
  std::string headerLine;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;

  /// Column index by name; fails the test (throws) when absent.
  std::size_t column(const std::string& name) const;
  const std::string& at(std::size_t row, const std::string& name) const {
    return rows[row][column(name)];
  }
};

CsvTable readCsv(const std::string& path);

}  // namespace adb::tradeoff::test
