// Bad input gets one clear message naming the flag or file and the value, a non-zero exit
// (2 for usage errors, 1 for input errors), and the results of the models before a bad
// mesh are kept.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "tool_run.h"

namespace adb::tradeoff::test {
namespace {

void expectUsageError(const std::vector<std::string>& args, const std::vector<std::string>& mentions) {
  // A directory per test: ctest may run the tests in parallel.
  const std::string dir =
      freshDir(std::string("usage_") + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::vector<std::string> full{"--no-plots", "--out", dir};
  full.insert(full.end(), args.begin(), args.end());
  const RunResult r = runTool(full);
  EXPECT_EQ(r.exitCode, 2) << r.stderrText;
  for (const std::string& m : mentions) {
    EXPECT_NE(r.stderrText.find(m), std::string::npos) << "stderr lacks '" << m << "':\n" << r.stderrText;
  }
  // Usage errors are caught before anything runs: no results were written.
  EXPECT_FALSE(std::filesystem::exists(dir + "/queries.csv"));
}

TEST(BadInput, UnknownMethodIsAUsageErrorNamingIt) {
  expectUsageError({"--model", "knot:1000", "--methods", "adb,bogus"}, {"--methods", "bogus"});
}

TEST(BadInput, MalformedNumbersAndRangesAreUsageErrorsNamingFlagAndValue) {
  expectUsageError({"--model", "knot:1000", "--distances", "2:0.4:0.1"}, {"--distances", "2:0.4:0.1"});
  expectUsageError({"--model", "knot:1000", "--distances", "0.4:2"}, {"--distances", "0.4:2"});
  expectUsageError({"--model", "knot:1000", "--distances", "0.4:2:0"}, {"--distances", "step"});
  expectUsageError({"--model", "knot:1000", "--rotations", "-3"}, {"--rotations", "-3"});
  expectUsageError({"--model", "knot:1000", "--rotations", "5x"}, {"--rotations", "5x"});
  expectUsageError({"--model", "knot:1000", "--p-min", "1.5"}, {"--p-min", "1.5"});
  expectUsageError({"--model", "knot:1000", "--k-min", "0"}, {"--k-min", "0"});
  expectUsageError({"--model", "knot:1000", "--budget-us", "abc"}, {"--budget-us", "abc"});
  expectUsageError({"--model", "knot:1000", "--seed"}, {"--seed: ", "missing"});
  expectUsageError({"--model", "knot:1000", "--budget-pairs", "0"}, {"--budget-pairs", "'0'"});
}

TEST(BadInput, UnknownModelAndMissingModelsAreUsageErrors) {
  expectUsageError({"--model", "teapot"}, {"--model", "teapot", "knot"});
  expectUsageError({"--model", "knot:12"}, {"--model", "knot:12"});
  expectUsageError({"--rotations", "5"}, {"--mesh", "--model"});
  expectUsageError({"--model", "knot:1000", "--frobnicate"}, {"--frobnicate"});
}

TEST(BadInput, PairsAndPosesMisusedAreUsageErrorsNamingTheOption) {
  expectUsageError({"--against-model", "robot"}, {"--against-model", "robot", "--mesh", "--model"});
  expectUsageError({"--against-mesh", "arm.stl", "--model", "room"},
                   {"--against-mesh", "arm.stl", "no --mesh or --model before it"});
  expectUsageError({"--model", "room", "--against-model", "chair"},
                   {"--against-model", "chair", "unknown model", "robot"});
  expectUsageError({"--model", "room", "--against-model", "robot", "--against-model", "knot"},
                   {"--against-model", "knot", "already tested against"});
  expectUsageError({"--model", "room:5000"}, {"--model", "room:5000", "fixed resolution"});
  expectUsageError({"--model", "knot:1000", "--poses", "around"}, {"--poses", "around"});
  expectUsageError({"--model", "knot:1000", "--poses", "inside", "--distances", "0.5"},
                   {"--distances", "--poses inside"});
}

TEST(BadInput, MissingAgainstMeshIsAnInputErrorNamingTheFile) {
  const std::string dir = freshDir("missing_against");
  const RunResult r = runTool({"--model", "knot:1000", "--against-mesh", dir + "/no_such_b.stl",
                               "--no-plots", "--out", dir});
  EXPECT_EQ(r.exitCode, 1) << r.stderrText;
  EXPECT_NE(r.stderrText.find("no_such_b.stl"), std::string::npos) << r.stderrText;
}

TEST(BadInput, MissingMeshFileIsAnInputErrorNamingTheFile) {
  const std::string dir = freshDir("missing");
  const RunResult r = runTool({"--mesh", dir + "/no_such_mesh.obj", "--no-plots", "--out", dir});
  EXPECT_EQ(r.exitCode, 1) << r.stderrText;
  EXPECT_NE(r.stderrText.find("no_such_mesh.obj"), std::string::npos) << r.stderrText;
}

TEST(BadInput, MeshWithNaNIsAnInputErrorNamingTheFile) {
  const std::string dir = freshDir("nan");
  const std::string file = dir + "/bad_vertex.obj";
  std::ofstream(file) << "v nan 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  const RunResult r = runTool({"--mesh", file, "--no-plots", "--out", dir});
  EXPECT_EQ(r.exitCode, 1) << r.stderrText;
  EXPECT_NE(r.stderrText.find("bad_vertex.obj"), std::string::npos) << r.stderrText;
}

TEST(BadInput, ResultsOfModelsBeforeABadMeshAreKept) {
  const std::string dir = freshDir("partial");
  const RunResult r = runTool({"--model", "torus:1000", "--mesh", dir + "/missing.obj",
                               "--model", "knot:1000", "--rotations", "2", "--distances",
                               "0.5,1.5", "--methods", "exact,fcl", "--repeats", "1",
                               "--no-plots", "--out", dir});
  EXPECT_EQ(r.exitCode, 1) << r.stderrText;
  EXPECT_NE(r.stderrText.find("missing.obj"), std::string::npos) << r.stderrText;

  const CsvTable q = readCsv(dir + "/queries.csv");
  EXPECT_EQ(q.rows.size(), 2u * 2u * 2u);  // torus: 2 distances x 2 rotations x 2 methods
  for (std::size_t i = 0; i < q.rows.size(); ++i) EXPECT_EQ(q.at(i, "model"), "torus");
  const CsvTable s = readCsv(dir + "/summary.csv");
  ASSERT_EQ(s.rows.size(), 2u);
  for (std::size_t i = 0; i < s.rows.size(); ++i) EXPECT_EQ(s.at(i, "model"), "torus");
  const CsvTable c = readCsv(dir + "/cells.csv");
  EXPECT_EQ(c.rows.size(), 512u);
}

}  // namespace
}  // namespace adb::tradeoff::test
