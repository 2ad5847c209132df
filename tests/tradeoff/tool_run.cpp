// Running adb-tradeoff from tests, and reading its CSVs.
#include "tool_run.h"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#ifndef ADB_TRADEOFF_EXE
#error "ADB_TRADEOFF_EXE (the path of adb-tradeoff) must be defined by the build"
#endif
#ifndef ADB_TRADEOFF_TEST_DIR
#error "ADB_TRADEOFF_TEST_DIR (a scratch directory in the build tree) must be defined"
#endif

namespace adb::tradeoff::test {
namespace {

std::string shellQuote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::vector<std::string> splitLine(const std::string& line) {
  std::vector<std::string> fields;
  std::string field;
  std::stringstream in(line);
  while (std::getline(in, field, ',')) fields.push_back(field);
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

}  // namespace

RunResult runTool(const std::vector<std::string>& args) {
  const std::string errFile = std::string(ADB_TRADEOFF_TEST_DIR) + "/stderr-" +
                              std::to_string(::getpid()) + ".txt";
  std::filesystem::create_directories(ADB_TRADEOFF_TEST_DIR);
  std::string command = shellQuote(ADB_TRADEOFF_EXE);
  for (const std::string& a : args) command += " " + shellQuote(a);
  command += " >/dev/null 2>" + shellQuote(errFile);
  const int status = std::system(command.c_str());
  RunResult r;
  r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(errFile);
  std::stringstream text;
  text << in.rdbuf();
  r.stderrText = text.str();
  std::filesystem::remove(errFile);
  return r;
}

std::string freshDir(const std::string& name) {
  const std::string dir = std::string(ADB_TRADEOFF_TEST_DIR) + "/" + name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

std::size_t CsvTable::column(const std::string& name) const {
  for (std::size_t i = 0; i < header.size(); ++i) {
    if (header[i] == name) return i;
  }
  throw std::runtime_error("no column " + name);
}

CsvTable readCsv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot read " + path);
  CsvTable t;
  std::getline(in, t.headerLine);
  t.header = splitLine(t.headerLine);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) t.rows.push_back(splitLine(line));
  }
  return t;
}

}  // namespace adb::tradeoff::test
