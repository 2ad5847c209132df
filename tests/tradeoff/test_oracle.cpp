// The ADB-tree's exact mode agrees with FCL (an independent exact library) on every query
// of a small run, on three models, at distances from deep overlap to apart, and on pairs of
// different models (at distances and inside poses).
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

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

// The same on pairs of different models, where exact mode walks two trees: the robot and the
// sliver cylinder anywhere in the room, and the sliver cylinder against the knot and the
// pipes against the gears at Zachmann's distances.
TEST(Oracle, ExactModeAgreesWithFclOnPairsOfDifferentModels) {
  const std::vector<std::vector<std::string>> runs{
      {"--model", "room", "--against-model", "robot", "--model", "room", "--against-model",
       "slivers:2000", "--poses", "inside", "--rotations", "150"},
      {"--model", "slivers:2000", "--against-model", "knot:2000", "--model", "pipes:3000",
       "--against-model", "gears:2000", "--rotations", "10", "--distances", "0.3:1.8:0.15"},
  };
  using Key = std::tuple<std::string, std::string, std::string>;  // model, distance, rotation
  std::map<Key, std::map<std::string, std::string>> answers;
  for (std::size_t k = 0; k < runs.size(); ++k) {
    const std::string dir = freshDir("oracle_pairs_" + std::to_string(k));
    std::vector<std::string> args = runs[k];
    args.insert(args.end(),
                {"--methods", "exact,fcl", "--repeats", "1", "--no-plots", "--out", dir});
    const RunResult run = runTool(args);
    ASSERT_EQ(run.exitCode, 0) << run.stderrText;
    const CsvTable t = readCsv(dir + "/queries.csv");
    for (std::size_t i = 0; i < t.rows.size(); ++i) {
      answers[Key{t.at(i, "model"), t.at(i, "distance"), t.at(i, "rotation")}]
             [t.at(i, "method")] = t.at(i, "collides");
    }
  }
  ASSERT_EQ(answers.size(), 2u * 150u + 2u * 11u * 10u);
  std::map<std::string, std::pair<int, int>> hitsAndQueries;  // per pair
  for (const auto& [key, byMethod] : answers) {
    ASSERT_EQ(byMethod.size(), 2u);
    EXPECT_EQ(byMethod.at("exact"), byMethod.at("fcl"))
        << std::get<0>(key) << " distance " << std::get<1>(key) << " rotation " << std::get<2>(key);
    auto& [hits, queries] = hitsAndQueries[std::get<0>(key)];
    hits += byMethod.at("exact") == "1" ? 1 : 0;
    ++queries;
  }
  ASSERT_EQ(hitsAndQueries.size(), 4u);  // room+robot, room+slivers, slivers+knot, pipes+gears
  for (const auto& [pair, counts] : hitsAndQueries) {
    // Both answers occur on every pair: the agreement is not vacuous.
    EXPECT_GT(counts.first, 5) << pair;
    EXPECT_LT(counts.first, counts.second - 5) << pair;
  }
}

}  // namespace
}  // namespace adb::tradeoff::test
