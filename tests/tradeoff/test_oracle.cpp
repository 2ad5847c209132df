// The ADB-tree's exact mode agrees with FCL (an independent exact library) on every query
// of a small run, on three models, at distances from deep overlap to apart.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <tuple>

#include "tool_run.h"

namespace adb::tradeoff::test {
namespace {

TEST(Oracle, ExactModeAgreesWithFclOnEveryQuery) {
  const std::string dir = freshDir("oracle");
  const RunResult run = runTool({"--model", "knot:2000", "--model", "pipes:3000", "--model",
                                 "gears:2000", "--rotations", "12", "--distances", "0.3:1.8:0.15",
                                 "--methods", "exact,fcl", "--repeats", "1", "--no-plots",
                                 "--out", dir});
  ASSERT_EQ(run.exitCode, 0) << run.stderrText;
  const CsvTable t = readCsv(dir + "/queries.csv");
  using Key = std::tuple<std::string, std::string, std::string>;  // model, distance, rotation
  std::map<Key, std::map<std::string, std::string>> answers;
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    answers[Key{t.at(i, "model"), t.at(i, "distance"), t.at(i, "rotation")}][t.at(i, "method")] =
        t.at(i, "collides");
  }
  ASSERT_EQ(answers.size(), 3u * 11u * 12u);
  int hits = 0;
  for (const auto& [key, byMethod] : answers) {
    ASSERT_EQ(byMethod.size(), 2u);
    EXPECT_EQ(byMethod.at("exact"), byMethod.at("fcl"))
        << std::get<0>(key) << " distance " << std::get<1>(key) << " rotation " << std::get<2>(key);
    hits += byMethod.at("exact") == "1" ? 1 : 0;
  }
  EXPECT_GT(hits, 20);
  EXPECT_LT(hits, static_cast<int>(answers.size()) - 20);
}

}  // namespace
}  // namespace adb::tradeoff::test
