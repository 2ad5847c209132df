// adb-bench-core: the core's performance figures (Google Benchmark).
//   build/bin/adb-bench-core                       # everything
//   build/bin/adb-bench-core --benchmark_filter=Build
// Reported in docs/core-results.md: tree build time per triangle count and counting algorithm,
// memory per triangle, and query time of ADB (p_min 0.99, k_min 10) against exact mode on the
// same poses.
#include <benchmark/benchmark.h>

#include <map>
#include <memory>

#include "adb/support/benchmark_poses.h"
#include "adb/support/mesh_generators.h"
#include "adb/core/query.h"
#include "adb/core/tree.h"

namespace {

// Meshes are generated once per size and kept: generation is not what is measured.
const adb::TriangleMesh& model(const std::string& name, std::size_t triangles) {
  static std::map<std::pair<std::string, std::size_t>, std::unique_ptr<adb::TriangleMesh>> cache;
  auto& slot = cache[{name, triangles}];
  if (!slot) slot = std::make_unique<adb::TriangleMesh>(adb::gen::makeModel(name, triangles));
  return *slot;
}

void buildBenchmark(benchmark::State& state, adb::CellCounting counting) {
  const adb::TriangleMesh& mesh = model("knot", static_cast<std::size_t>(state.range(0)));
  adb::BuildSettings settings;
  settings.counting = counting;
  double hierarchy = 0.0, counts = 0.0;
  std::size_t bytes = 0;
  for (auto _ : state) {
    adb::AdbTree tree(mesh, settings);
    hierarchy += tree.hierarchySeconds();
    counts += tree.countingSeconds();
    bytes = tree.memoryBytes();
    benchmark::DoNotOptimize(tree.root().pc);
  }
  const double n = static_cast<double>(state.iterations());
  state.counters["triangles"] = static_cast<double>(mesh.triangleCount());
  state.counters["hierarchy_s"] = hierarchy / n;
  state.counters["counting_s"] = counts / n;
  state.counters["s_per_100k"] = (hierarchy + counts) / n * 1e5 / static_cast<double>(mesh.triangleCount());
  state.counters["bytes_per_tri"] = static_cast<double>(bytes) / static_cast<double>(mesh.triangleCount());
}

void BM_BuildApproximate(benchmark::State& state) {
  buildBenchmark(state, adb::CellCounting::Approximate);
}
void BM_BuildExact(benchmark::State& state) { buildBenchmark(state, adb::CellCounting::Exact); }
BENCHMARK(BM_BuildApproximate)->Arg(10000)->Arg(100000)->Arg(1000000)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_BuildExact)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond)->Iterations(1);

// Query time at one benchmark distance (x10 in the argument), averaged over 200 fixed poses.
void queryBenchmark(benchmark::State& state, adb::QueryMode mode, const std::string& name) {
  const adb::TriangleMesh& mesh = model(name, static_cast<std::size_t>(state.range(1)));
  static std::map<const adb::TriangleMesh*, std::unique_ptr<adb::AdbTree>> trees;
  auto& tree = trees[&mesh];
  if (!tree) tree = std::make_unique<adb::AdbTree>(mesh);
  std::mt19937_64 rng(1);
  std::vector<adb::PosePair> poses;
  for (int i = 0; i < 200; ++i) {
    poses.push_back(adb::benchmarkPoses(mesh.bounds(), static_cast<double>(state.range(0)) / 10.0, rng));
  }
  adb::QuerySettings settings;
  settings.mode = mode;
  adb::QueryScratch scratch;
  std::size_t i = 0, collisions = 0, queries = 0;
  for (auto _ : state) {
    const adb::PosePair& p = poses[i++ % poses.size()];
    const adb::QueryResult r = adb::collide(*tree, p.a, *tree, p.b, settings, scratch);
    collisions += r.collides ? 1 : 0;
    ++queries;
  }
  state.counters["collide_rate"] = static_cast<double>(collisions) / static_cast<double>(queries);
}

void BM_QueryAdb(benchmark::State& state) { queryBenchmark(state, adb::QueryMode::Adb, "knot"); }
void BM_QueryExact(benchmark::State& state) {
  queryBenchmark(state, adb::QueryMode::Exact, "knot");
}
void queryArgs(benchmark::internal::Benchmark* b) {
  for (int tris : {10000, 100000}) {
    for (int d10 : {5, 10, 15, 20}) b->Args({d10, tris});
  }
  b->Unit(benchmark::kMicrosecond);
}
BENCHMARK(BM_QueryAdb)->Apply(queryArgs);
BENCHMARK(BM_QueryExact)->Apply(queryArgs);

// 50 seeded benchmark poses at each distance 0.4, 0.5, ..., 2.0: 850 in all.
std::vector<adb::PosePair> poseSet(const adb::TriangleMesh& mesh) {
  std::mt19937_64 rng(1);
  std::vector<adb::PosePair> poses;
  for (int step = 0; step <= 16; ++step) {
    for (int r = 0; r < 50; ++r) {
      poses.push_back(adb::benchmarkPoses(mesh.bounds(), 0.4 + 0.1 * step, rng));
    }
  }
  return poses;
}

// The fixed query set behind the cost per node pair (docs/probability-model.md section 6):
// the knot at 20k triangles, distances 0.4 to 2.0 in steps of 0.1 with 50 rotations each
// (seed 1): 850 poses, all queried twice, once per run. node_pairs is the total. Under
// callgrind, collide's inclusive instruction count divided by the node_pairs counter is the
// cost of a node pair, repeatably on a shared machine:
//   valgrind --tool=callgrind --callgrind-out-file=cg build/bin/adb-bench-core
//       --benchmark_filter=nodePairCost/adb   (one command line)
//   callgrind_annotate --inclusive=yes cg | grep 'adb::collide('
void nodePairCost(benchmark::State& state, adb::QueryMode mode) {
  const adb::TriangleMesh& mesh = model("knot", 20000);
  const adb::AdbTree tree(mesh);
  const std::vector<adb::PosePair> poses = poseSet(mesh);
  adb::QuerySettings settings;
  settings.mode = mode;
  adb::QueryScratch scratch;
  double nodePairs = 0.0;
  for (auto _ : state) {
    for (int repeat = 0; repeat < 2; ++repeat) {
      for (const adb::PosePair& p : poses) {
        const adb::QueryResult r = adb::collide(tree, p.a, tree, p.b, settings, scratch);
        nodePairs += static_cast<double>(r.nodePairs);
      }
    }
  }
  state.counters["node_pairs"] = nodePairs;
}
BENCHMARK_CAPTURE(nodePairCost, adb, adb::QueryMode::Adb)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(nodePairCost, exact, adb::QueryMode::Exact)
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

// Exact mode's first hit in the trees' order against most expected cells first
// (ExactDescent::MostCellsFirst), on the same poses: time per query and node pairs.
void exactFirstHit(benchmark::State& state, const char* name, adb::ExactDescent descent) {
  const adb::TriangleMesh& mesh = model(name, 20000);
  const adb::AdbTree tree(mesh);
  const std::vector<adb::PosePair> poses = poseSet(mesh);
  adb::QuerySettings settings;
  settings.mode = adb::QueryMode::Exact;
  settings.stopAtFirstHit = true;
  settings.descent = descent;
  adb::QueryScratch scratch;
  double nodePairs = 0.0;
  for (auto _ : state) {
    for (const adb::PosePair& p : poses) {
      nodePairs += static_cast<double>(
          adb::collide(tree, p.a, tree, p.b, settings, scratch).nodePairs);
    }
  }
  state.counters["node_pairs_per_query"] = benchmark::Counter(
      nodePairs / static_cast<double>(poses.size()), benchmark::Counter::kAvgIterations);
  state.counters["queries"] = static_cast<double>(poses.size());  // the time is for all of them
}
BENCHMARK_CAPTURE(exactFirstHit, knot_tree_order, "knot", adb::ExactDescent::TreeOrder)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(exactFirstHit, knot_most_cells, "knot", adb::ExactDescent::MostCellsFirst)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(exactFirstHit, gears_tree_order, "gears", adb::ExactDescent::TreeOrder)
    ->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(exactFirstHit, gears_most_cells, "gears", adb::ExactDescent::MostCellsFirst)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
