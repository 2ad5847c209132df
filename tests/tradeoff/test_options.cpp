// adb-tradeoff's flag parsing: ranges, lists, defaults, and errors naming flag and value.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "options.h"

namespace adb::tradeoff {
namespace {

Options parse(std::vector<const char*> args) {
  args.insert(args.begin(), "adb-tradeoff");
  return parseOptions(static_cast<int>(args.size()), args.data());
}

std::string errorOf(std::vector<const char*> args) {
  try {
    parse(std::move(args));
  } catch (const UsageError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(Options, DefaultsFollowTheIssue) {
  const Options o = parse({"--model", "knot"});
  ASSERT_EQ(o.cases.size(), 1u);
  EXPECT_EQ(o.cases[0].a.name, "knot");
  EXPECT_EQ(o.cases[0].a.targetTriangles, 20000u);
  EXPECT_FALSE(o.cases[0].b);  // a second copy of the model
  EXPECT_EQ(o.poses, PoseMode::Distances);
  ASSERT_EQ(o.distances.size(), 17u);  // 0.4, 0.5, ..., 2.0
  EXPECT_EQ(o.distances.front(), 0.4);
  EXPECT_EQ(o.distances[3], 0.7);  // no 0.70000000000000007 from 0.4 + 3 * 0.1
  EXPECT_EQ(o.distances.back(), 2.0);
  EXPECT_EQ(o.rotations, 200);
  EXPECT_EQ(o.methods, (std::vector<std::string>{"adb", "exact", "gimpact", "fcl"}));
  EXPECT_EQ(o.kMins, (std::vector<int>{1, 5, 10}));
  ASSERT_EQ(o.budgetsUs.size(), 4u);
  EXPECT_TRUE(std::isinf(o.budgetsUs[0]));
  EXPECT_EQ(o.budgetsUs[3], 100.0);
  EXPECT_TRUE(o.plots);
  EXPECT_TRUE(o.budgetPairs.empty());  // no work-budget runs unless asked for
  EXPECT_FALSE(o.exactCounting);       // the paper's fast approximate counts
}

TEST(Options, ExactCountingIsASwitch) {
  EXPECT_TRUE(parse({"--model", "knot", "--exact-counting"}).exactCounting);
  EXPECT_NE(errorOf({"--model", "knot", "--exact-counting=1"}).find("exact-counting"),
            std::string::npos);
}

TEST(Options, SourcesKeepCommandLineOrder) {
  const Options o = parse({"--model", "torus:1000", "--mesh", "a/b.obj", "--model", "gears:5000"});
  ASSERT_EQ(o.cases.size(), 3u);
  EXPECT_EQ(o.cases[0].a.name, "torus");
  EXPECT_EQ(o.cases[0].a.targetTriangles, 1000u);
  EXPECT_EQ(o.cases[1].a.kind, ModelSource::Kind::File);
  EXPECT_EQ(o.cases[1].a.path, "a/b.obj");
  EXPECT_EQ(o.cases[2].a.targetTriangles, 5000u);
  EXPECT_EQ(fileStem("a/b.obj"), "b");
}

// --against-mesh and --against-model give the second body of the case begun just before them.
TEST(Options, AgainstPairsWithTheModelJustBeforeIt) {
  const Options o = parse({"--model", "room", "--against-model", "robot", "--mesh", "a/arm.stl",
                           "--against-mesh", "b/shaft.stl", "--model", "knot:2000",
                           "--mesh", "c.obj", "--against-model", "slivers:5000"});
  ASSERT_EQ(o.cases.size(), 4u);
  EXPECT_EQ(o.cases[0].a.kind, ModelSource::Kind::Fixed);
  EXPECT_EQ(o.cases[0].a.name, "room");
  ASSERT_TRUE(o.cases[0].b);
  EXPECT_EQ(o.cases[0].b->kind, ModelSource::Kind::Fixed);
  EXPECT_EQ(o.cases[0].b->name, "robot");
  EXPECT_EQ(o.cases[1].a.path, "a/arm.stl");
  ASSERT_TRUE(o.cases[1].b);
  EXPECT_EQ(o.cases[1].b->kind, ModelSource::Kind::File);
  EXPECT_EQ(o.cases[1].b->path, "b/shaft.stl");
  EXPECT_FALSE(o.cases[2].b);
  ASSERT_TRUE(o.cases[3].b);
  EXPECT_EQ(o.cases[3].b->kind, ModelSource::Kind::Generated);
  EXPECT_EQ(o.cases[3].b->name, "slivers");
  EXPECT_EQ(o.cases[3].b->targetTriangles, 5000u);
  EXPECT_EQ(sourceLabel(o.cases[1].b.value()), "shaft");
}

TEST(Options, AgainstNeedsAModelBeforeItAndOnlyOne) {
  for (const char* flag : {"--against-model", "--against-mesh"}) {
    const std::string alone = errorOf({flag, "robot", "--model", "room"});
    EXPECT_EQ(alone.rfind(std::string(flag) + " 'robot'", 0), 0u) << alone;
    EXPECT_NE(alone.find("no --mesh or --model before it"), std::string::npos) << alone;
  }
  const std::string twice =
      errorOf({"--model", "room", "--against-model", "robot", "--against-mesh", "x.stl"});
  EXPECT_EQ(twice.rfind("--against-mesh 'x.stl'", 0), 0u) << twice;
  EXPECT_NE(twice.find("already tested against 'robot'"), std::string::npos) << twice;
  const std::string unknown = errorOf({"--model", "room", "--against-model", "chair"});
  EXPECT_EQ(unknown.rfind("--against-model 'chair': unknown model", 0), 0u) << unknown;
  EXPECT_NE(unknown.find("robot"), std::string::npos) << unknown;  // the names are listed
  EXPECT_EQ(errorOf({"--model", "room", "--against-mesh", ""}).rfind("--against-mesh", 0), 0u);
}

// The real-mesh models: slivers follows a target like the benchmark's; room and robot have
// one resolution, and a count after them is refused rather than ignored.
TEST(Options, RealMeshModelsAndTheirTriangleCounts) {
  const Options o = parse({"--model", "slivers:3000", "--model", "robot"});
  EXPECT_EQ(o.cases[0].a.kind, ModelSource::Kind::Generated);
  EXPECT_EQ(o.cases[0].a.targetTriangles, 3000u);
  EXPECT_EQ(o.cases[1].a.kind, ModelSource::Kind::Fixed);
  EXPECT_EQ(parse({"--model", "slivers"}).cases[0].a.targetTriangles, 20000u);
  const std::string counted = errorOf({"--model", "room:2000"});
  EXPECT_EQ(counted.rfind("--model 'room:2000'", 0), 0u) << counted;
  EXPECT_NE(counted.find("fixed resolution"), std::string::npos) << counted;
  EXPECT_EQ(errorOf({"--model", "knot", "--against-model", "robot:500"})
                .rfind("--against-model 'robot:500'", 0),
            0u);
  EXPECT_NE(errorOf({"--model", "slivers:10"}).find("between 1000 and 1000000"),
            std::string::npos);
}

TEST(Options, PosesInsideTakesNoDistances) {
  const Options o = parse({"--model", "room", "--against-model", "robot", "--poses", "inside",
                           "--rotations", "50"});
  EXPECT_EQ(o.poses, PoseMode::Inside);
  EXPECT_EQ(o.rotations, 50);
  EXPECT_EQ(parse({"--model", "knot", "--poses", "distances"}).poses, PoseMode::Distances);
  const std::string bad = errorOf({"--model", "knot", "--poses", "outside"});
  EXPECT_EQ(bad.rfind("--poses 'outside'", 0), 0u) << bad;
  // Either order: --distances means nothing to inside poses.
  for (const auto& args : {std::vector<const char*>{"--model", "knot", "--poses", "inside",
                                                    "--distances", "0.5"},
                           std::vector<const char*>{"--model", "knot", "--distances", "0.5",
                                                    "--poses", "inside"}}) {
    const std::string e = errorOf(args);
    EXPECT_EQ(e.rfind("--distances", 0), 0u) << e;
    EXPECT_NE(e.find("--poses inside"), std::string::npos) << e;
  }
}

TEST(Options, DistancesMixNumbersAndRanges) {
  const Options o = parse({"--model", "knot", "--distances", "1.5,0.4:1.2:0.4", "--no-plots"});
  EXPECT_EQ(o.distances, (std::vector<double>{0.4, 0.8, 1.2, 1.5}));
  EXPECT_FALSE(o.plots);
}

TEST(Options, ErrorsNameTheFlagAndTheValue) {
  EXPECT_NE(errorOf({"--model", "knot", "--distances", "2:0.4:0.1"}).find("--distances '2:0.4:0.1'"),
            std::string::npos);
  EXPECT_NE(errorOf({"--model", "knot", "--rotations", "-3"}).find("--rotations '-3'"),
            std::string::npos);
  EXPECT_NE(errorOf({"--model", "knot", "--p-min", "0.5,1.5"}).find("--p-min '1.5'"),
            std::string::npos);
  EXPECT_NE(errorOf({"--model", "knot", "--k-min", "0"}).find("--k-min '0'"), std::string::npos);
  EXPECT_NE(errorOf({"--model", "knot", "--budget-us", "abc"}).find("--budget-us 'abc'"),
            std::string::npos);
  EXPECT_NE(errorOf({"--model", "knot", "--methods", "adb,adb"}).find("twice"), std::string::npos);
  EXPECT_NE(errorOf({"--model", "knot:2000000"}).find("--model 'knot:2000000'"), std::string::npos);
  EXPECT_NE(errorOf({}).find("--mesh"), std::string::npos);
}

TEST(Options, BudgetPairsAreAListOfPositiveNodePairCounts) {
  const Options o = parse({"--model", "knot", "--budget-pairs", "100,20000,7"});
  EXPECT_EQ(o.budgetPairs, (std::vector<std::uint64_t>{100, 20000, 7}));
  EXPECT_EQ(parse({"--model", "knot", "--budget-pairs=1"}).budgetPairs,
            (std::vector<std::uint64_t>{1}));
}

TEST(Options, BadBudgetPairsGiveOneErrorNamingTheFlagAndTheValue) {
  for (const char* bad : {"0", "-5", "1.5", "abc", "10,,20", "99999999999999999999"}) {
    const std::string e = errorOf({"--model", "knot", "--budget-pairs", bad});
    EXPECT_EQ(e.rfind("--budget-pairs '", 0), 0u) << bad << ": " << e;
  }
  EXPECT_NE(errorOf({"--model", "knot", "--budget-pairs", "0"}).find("'0'"), std::string::npos);
  EXPECT_NE(errorOf({"--model", "knot", "--budget-pairs", "10,x"}).find("'x'"),
            std::string::npos);
  EXPECT_NE(errorOf({"--model", "knot", "--budget-pairs", ""}).find("--budget-pairs"),
            std::string::npos);
  EXPECT_NE(errorOf({"--model", "knot", "--budget-pairs", "5,5"}).find("twice"),
            std::string::npos);
  // A flag without its value: CLI11's wording ("--budget-pairs: 1 required LIST missing").
  const std::string missing = errorOf({"--model", "knot", "--budget-pairs"});
  EXPECT_EQ(missing.rfind("--budget-pairs: ", 0), 0u) << missing;
  EXPECT_NE(missing.find("missing"), std::string::npos) << missing;
}

TEST(Options, NewMethodsAreOptInAndBudgetedOnesNeedAFiniteBudget) {
  const Options o = parse({"--model", "knot", "--methods", "exact-cut,box-first,root-boxes,adb"});
  EXPECT_EQ(o.methods,
            (std::vector<std::string>{"exact-cut", "box-first", "root-boxes", "adb"}));
  for (const char* method : {"exact-cut", "box-first"}) {
    const std::string e =
        errorOf({"--model", "knot", "--methods", method, "--budget-us", "none"});
    EXPECT_NE(e.find(std::string("--methods '") + method + "'"), std::string::npos) << e;
    EXPECT_NE(e.find("--budget-us"), std::string::npos) << e;
  }
  // root-boxes needs no budget.
  EXPECT_EQ(parse({"--model", "knot", "--methods", "root-boxes", "--budget-us", "none"}).methods,
            (std::vector<std::string>{"root-boxes"}));
  const std::string unknown = errorOf({"--model", "knot", "--methods", "box-last"});
  EXPECT_NE(unknown.find("--methods 'box-last'"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("root-boxes"), std::string::npos) << unknown;  // the list is complete
}

TEST(Options, HelpNamesTheNewMethodsAndFlag) {
  const std::string help = usageText();
  for (const char* word : {"--budget-pairs", "adb-work:N", "exact-cut", "box-first",
                           "root-boxes", "reliability.csv", "ece", "slivers", "room", "robot",
                           "A+B", "the mean of", "inside"}) {
    EXPECT_NE(help.find(word), std::string::npos) << word;
  }
}

// --help is built by CLI11 from the flags themselves: every flag is listed, with the defaults
// the parser really uses.
TEST(Options, HelpListsEveryFlagWithItsDefault) {
  const std::string help = usageText();
  for (const char* flag : {"--mesh", "--model", "--against-mesh", "--against-model", "--poses",
                           "--distances", "--rotations", "--seed",
                           "--methods", "--p-min", "--k-min", "--budget-us", "--budget-pairs",
                           "--exact-counting", "--repeats", "--out", "--no-plots", "--help"}) {
    EXPECT_NE(help.find(flag), std::string::npos) << flag;
  }
  for (const char* value : {"0.4:2.0:0.1", "=200", "adb,exact,gimpact,fcl", "0.5,0.9,0.99",
                            "=distances",
                            "1,5,10", "none,5,20,100", "=3", "tradeoff-results"}) {
    EXPECT_NE(help.find(value), std::string::npos) << value;
  }
  // --help needs nothing else (not even a model) and stops there.
  EXPECT_TRUE(parse({"--help"}).help);
  EXPECT_TRUE(parse({"-h"}).help);
}

TEST(Options, ARepeatedFlagKeepsItsLastValue) {
  const Options o = parse({"--model", "knot", "--rotations", "5", "--rotations=7"});
  EXPECT_EQ(o.rotations, 7);
}

// A switch: "--no-plots=false" is an error, not a double negative (CLI11 names the flag
// without its dashes here).
TEST(Options, NoPlotsTakesNoValue) {
  const std::string e = errorOf({"--model", "knot", "--no-plots=false"});
  EXPECT_NE(e.find("no-plots"), std::string::npos) << e;
}

}  // namespace
}  // namespace adb::tradeoff
