// adb.collide (one query, with its witnesses) and adb.collide_many (K poses on a thread pool,
// the GIL released, answers as numpy arrays).
#include <pybind11/stl.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <exception>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "adb/core/errors.h"
#include "adb/core/query.h"
#include "adb/core/triangle_contact.h"
#include "adb/support/benchmark_poses.h"
#include "arrays.h"
#include "bindings.h"
#include "settings.h"

namespace adb::python {
namespace {

using TreePtr = std::shared_ptr<const AdbTree>;

/// One query's answer, with what its witnesses need to be read in mesh terms.
struct Result {
  QueryResult result;
  std::vector<Witness> witnesses;
  TreePtr a, b;
  Pose poseA, poseB;
};

// A triangle of `tree` (tree order) in world coordinates.
std::array<Vec3, 3> worldTriangle(const AdbTree& tree, const Pose& pose, std::uint32_t t) {
  const Triangle& tri = tree.triangles()[t];
  std::array<Vec3, 3> out;
  for (int c = 0; c < 3; ++c) out[c] = pose.apply(tree.localVertices()[tri[c]] + tree.origin());
  return out;
}

py::array_t<std::int64_t> witnessTriangles(const Result& r) {
  py::array_t<std::int64_t> out =
      newArray<std::int64_t>({static_cast<py::ssize_t>(r.witnesses.size()), 2});
  std::int64_t* p = out.mutable_data();
  for (const Witness& w : r.witnesses) {
    *p++ = w.isExact() ? r.a->meshTriangle(w.triangleA) : -1;
    *p++ = w.isExact() ? r.b->meshTriangle(w.triangleB) : -1;
  }
  return out;
}

// Contact points of the exact witnesses (NaN rows for node witnesses): the point on B, the
// normal from A towards B and the depth, from the two triangles (triangle_contact.h).
py::dict witnessContacts(const Result& r) {
  const auto n = static_cast<py::ssize_t>(r.witnesses.size());
  py::array_t<double> points = newArray<double>({n, 3});
  py::array_t<double> normals = newArray<double>({n, 3});
  py::array_t<double> depths = newArray<double>({n});
  for (py::ssize_t i = 0; i < n; ++i) {
    const Witness& w = r.witnesses[static_cast<std::size_t>(i)];
    TriangleContact c;
    c.pointOnB = c.normal = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
    c.depth = std::numeric_limits<double>::quiet_NaN();
    if (w.isExact()) {
      const auto ta = worldTriangle(*r.a, r.poseA, w.triangleA);
      const auto tb = worldTriangle(*r.b, r.poseB, w.triangleB);
      c = triangleContact(ta[0], ta[1], ta[2], tb[0], tb[1], tb[2], Vec3::Zero());  // no hint: the minimum translation
    }
    for (int k = 0; k < 3; ++k) {
      points.mutable_at(i, k) = c.pointOnB[k];
      normals.mutable_at(i, k) = c.normal[k];
    }
    depths.mutable_at(i) = c.depth;
  }
  py::dict d;
  d["points"] = points;
  d["normals"] = normals;
  d["depths"] = depths;
  return d;
}

void bindResult(py::module_& m) {
  py::class_<Result>(m, "Result", "The answer of adb.collide.")
      .def_property_readonly("collides", [](const Result& r) { return r.result.collides; },
                             "Whether the meshes intersect (the more probable answer when "
                             "the query was cut or stopped at the quality target).")
      .def_property_readonly(
          "confidence", [](const Result& r) { return r.result.confidence; },
          "The probability, in [0, 1], that `collides` is right: 1 when certain.")
      .def_property_readonly(
          "stop", [](const Result& r) { return std::string(toString(r.result.stop)); },
          "Why the query stopped: 'completed', 'quality reached', 'exact hit', 'time budget', "
          "'work budget' or 'witnesses full'.")
      .def_property_readonly("node_pairs", [](const Result& r) { return r.result.nodePairs; },
                             "Node pairs evaluated (what budget_pairs counts).")
      .def_property_readonly(
          "triangle_tests", [](const Result& r) { return r.result.triangleTests; },
          "Triangle-triangle tests run.")
      .def_property_readonly("seconds", [](const Result& r) { return r.result.seconds; },
                             "Wall clock of the query.")
      .def_property_readonly("witnesses", &witnessTriangles,
                             "(W, 2) int64: the mesh triangle indices of each intersecting "
                             "pair found (A's, B's); -1 for a node pair accepted on "
                             "probability. Empty when the answer is no.")
      .def_property_readonly(
          "witness_probabilities",
          [](const Result& r) {
            py::array_t<double> out = newArray<double>({static_cast<py::ssize_t>(r.witnesses.size())});
            for (std::size_t i = 0; i < r.witnesses.size(); ++i) {
              out.mutable_at(static_cast<py::ssize_t>(i)) = r.witnesses[i].probability;
            }
            return out;
          },
          "(W,) float64: 1 for intersecting triangles, the pair's probability otherwise.")
      .def("contacts", &witnessContacts,
           "Contact points of the intersecting triangle pairs in world coordinates: a dict of "
           "'points' (W, 3, on B), 'normals' (W, 3, from A towards B) and 'depths' (W,); NaN "
           "rows for node witnesses.")
      .def("__bool__", [](const Result& r) { return r.result.collides; })
      .def("__repr__", [](const Result& r) {
        return std::string("<adb.Result collides=") + (r.result.collides ? "True" : "False") +
               " confidence=" + std::to_string(r.result.confidence) + " stop='" +
               toString(r.result.stop) + "' node_pairs=" + std::to_string(r.result.nodePairs) +
               ">";
      });
}

QueryOptions options(const std::string& mode, double pMin, long long kMin,
                     std::optional<double> budgetUs, std::optional<long long> budgetPairs,
                     std::optional<bool> stopAtFirstHit, long long maxWitnesses,
                     double contactMargin) {
  return QueryOptions{mode,           pMin,         kMin,         budgetUs,
                      budgetPairs,    stopAtFirstHit, maxWitnesses, contactMargin};
}

Result collideOnce(const TreePtr& a, const py::handle& poseA, const TreePtr& b,
                   const py::handle& poseB, const QueryOptions& o) {
  const QuerySettings settings = querySettings(o);
  Result r;
  r.a = a;
  r.b = b;
  r.poseA = poseFrom(poseA, "pose_a");
  r.poseB = poseFrom(poseB, "pose_b");
  {
    py::gil_scoped_release release;
    thread_local QueryScratch scratch;  // grown once per thread: repeated queries allocate
                                        // nothing but their witness copy
    r.result = collide(*a, r.poseA, *b, r.poseB, settings, scratch);
    r.witnesses.assign(scratch.witnesses().begin(), scratch.witnesses().end());
  }
  return r;
}

/// The answers of collide_many, one entry per pose.
struct Batch {
  std::vector<QueryResult> results;
  std::vector<std::array<std::int64_t, 2>> firstWitness;
};

// Runs the K queries on `threads` threads (0: all), each thread with its own scratch.
Batch collideBatch(const AdbTree& a, const std::vector<Pose>& posesA, const AdbTree& b,
                   const std::vector<Pose>& posesB, const QuerySettings& settings, int threads) {
  const std::size_t k = posesA.size();
  Batch batch;
  batch.results.resize(k);
  batch.firstWitness.assign(k, {-1, -1});
  auto one = [&](std::size_t i, QueryScratch& scratch) {
    batch.results[i] = collide(a, posesA[i], b, posesB[i], settings, scratch);
    for (const Witness& w : scratch.witnesses()) {
      if (!w.isExact()) continue;
      batch.firstWitness[i] = {a.meshTriangle(w.triangleA), b.meshTriangle(w.triangleB)};
      break;
    }
  };
  if (threads == 1 || k < 2) {
    QueryScratch scratch;
    for (std::size_t i = 0; i < k; ++i) one(i, scratch);
    return batch;
  }
  // Settings and poses were checked before: collide() cannot throw here but for memory; the
  // first error in pose order is rethrown once all have ended, so nothing leaves a worker.
  std::vector<std::exception_ptr> errors(k);
  tbb::enumerable_thread_specific<QueryScratch> scratches;
  tbb::task_arena arena(threads == 0 ? tbb::task_arena::automatic : threads);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, k, 16),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        QueryScratch& scratch = scratches.local();
                        for (std::size_t i = range.begin(); i != range.end(); ++i) {
                          try {
                            one(i, scratch);
                          } catch (...) {
                            errors[i] = std::current_exception();
                          }
                        }
                      });
  });
  for (const std::exception_ptr& e : errors) {
    if (e) std::rethrow_exception(e);
  }
  return batch;
}

py::dict batchArrays(const Batch& batch) {
  const auto k = static_cast<py::ssize_t>(batch.results.size());
  py::array_t<bool> collides = newArray<bool>({k});
  py::array_t<double> confidence = newArray<double>({k});
  py::array_t<std::uint64_t> nodePairs = newArray<std::uint64_t>({k});
  py::array_t<std::uint64_t> triangleTests = newArray<std::uint64_t>({k});
  py::array_t<double> seconds = newArray<double>({k});
  py::array_t<std::int64_t> witness = newArray<std::int64_t>({k, 2});
  // Stop reasons as a numpy string array, written in place (no Python string per query).
  constexpr py::ssize_t kStopChars = 16;
  py::array stops(py::dtype("<U16"), std::vector<py::ssize_t>{k});
  auto* stopChars = static_cast<char32_t*>(stops.mutable_data());
  std::fill(stopChars, stopChars + k * kStopChars, U'\0');
  for (py::ssize_t i = 0; i < k; ++i) {
    const QueryResult& r = batch.results[static_cast<std::size_t>(i)];
    collides.mutable_at(i) = r.collides;
    confidence.mutable_at(i) = r.confidence;
    nodePairs.mutable_at(i) = r.nodePairs;
    triangleTests.mutable_at(i) = r.triangleTests;
    seconds.mutable_at(i) = r.seconds;
    witness.mutable_at(i, 0) = batch.firstWitness[static_cast<std::size_t>(i)][0];
    witness.mutable_at(i, 1) = batch.firstWitness[static_cast<std::size_t>(i)][1];
    const char* stop = toString(r.stop);
    for (py::ssize_t c = 0; c < kStopChars && stop[c] != '\0'; ++c) {
      stopChars[i * kStopChars + c] = static_cast<char32_t>(stop[c]);
    }
  }
  py::dict d;
  d["collides"] = collides;
  d["confidence"] = confidence;
  d["stop"] = stops;
  d["node_pairs"] = nodePairs;
  d["triangle_tests"] = triangleTests;
  d["seconds"] = seconds;
  d["witness"] = witness;
  return d;
}

}  // namespace

void bindQueries(py::module_& m) {
  bindResult(m);
  m.def(
      "check_pose",
      [](const py::handle& pose, const std::string& name) { return poseArray(poseFrom(pose, name)); },
      py::arg("pose"), py::arg("name") = "pose",
      "The pose as a (4, 4) float64 array, after the checks every adb call makes: a (4, 4) "
      "or (3, 4) array of finite real numbers, last row [0, 0, 0, 1], an orthonormal "
      "rotation. Raises PoseError naming `name` and what is wrong.");
  m.def(
      "poses_from_quaternions",
      [](const py::handle& quaternions, const py::handle& translations) {
        return poseArrays(posesFromQuaternions(quaternions, translations));
      },
      py::arg("quaternions"), py::arg("translations"),
      "(K, 4, 4) poses from (K, 4) quaternions [w, x, y, z] (normalised here) and (K, 3) "
      "translations, computed as adb's C++ does (adb::Pose::fromQuaternion): the poses of "
      "adb-tradeoff's per-query CSV become the very poses it queried.");
  m.def(
      "benchmark_poses",
      [](const TriangleMesh& mesh, const py::handle& distances, unsigned long long seed) {
        const std::vector<double> d = realsFrom(distances, "distances");
        std::vector<Pose> a(d.size()), b(d.size());
        std::mt19937_64 rng(seed);
        for (std::size_t k = 0; k < d.size(); ++k) {
          const PosePair pair = benchmarkPoses(mesh.bounds(), d[k], rng);
          a[k] = pair.a;
          b[k] = pair.b;
        }
        return py::make_tuple(poseArrays(a), poseArrays(b));
      },
      py::arg("mesh"), py::arg("distances"), py::kw_only(), py::arg("seed") = 1,
      "Two copies of `mesh` for each distance, as docs/benchmark.md places them: each turned "
      "at random about its bounding box's centre, the centres `distance` benchmark units "
      "apart along x (the unit: half the box's largest edge). Returns (poses_a, poses_b), "
      "(K, 4, 4) each; the same seed gives the same poses.");
  m.def(
      "collide",
      [](const TreePtr& a, const py::handle& poseA, const TreePtr& b, const py::handle& poseB,
         const std::string& mode, double pMin, long long kMin, std::optional<double> budgetUs,
         std::optional<long long> budgetPairs, std::optional<bool> stopAtFirstHit,
         long long maxWitnesses, double contactMargin) {
        return collideOnce(a, poseA, b, poseB,
                           options(mode, pMin, kMin, budgetUs, budgetPairs, stopAtFirstHit,
                                   maxWitnesses, contactMargin));
      },
      py::arg("tree_a").none(false), py::arg("pose_a"), py::arg("tree_b").none(false),
      py::arg("pose_b"),
      ADB_QUERY_KWARGS,
      "Tests tree_a at pose_a against tree_b at pose_b (poses: 4x4 or 3x4 rigid transforms "
      "from each mesh's coordinates to the world).\n\n"
      "mode='adb': the paper's traversal, most probable node pairs first, stopping once "
      "k_min node pairs have a probability above p_min, or at a budget. mode='exact': every "
      "overlapping pair down to triangle pairs (stop_at_first_hit=False collects every "
      "intersecting pair, up to max_witnesses). budget_us: wall-clock budget in microseconds; "
      "budget_pairs: node pairs at most (reproducible). contact_margin: triangle pairs closer "
      "than this count as hits. Returns a Result; its confidence says how sure the answer "
      "is. Raises SettingsError and PoseError naming a bad argument.");
  m.def(
      "collide_many",
      [](const TreePtr& a, const py::handle& posesA, const TreePtr& b, const py::handle& posesB,
         const std::string& mode, double pMin, long long kMin, std::optional<double> budgetUs,
         std::optional<long long> budgetPairs, std::optional<bool> stopAtFirstHit,
         long long maxWitnesses, double contactMargin, long long threads) {
        const QuerySettings settings = querySettings(options(
            mode, pMin, kMin, budgetUs, budgetPairs, stopAtFirstHit, maxWitnesses, contactMargin));
        if (threads < 0 || threads > 4096) {
          throw SettingsError("threads: " + std::to_string(threads) +
                              ", expected 0 (all hardware threads) or a count from 1 to 4096");
        }
        const std::optional<std::size_t> ka = batchSize(posesA, "poses_a");
        const std::optional<std::size_t> kb = batchSize(posesB, "poses_b");
        if (ka && kb && *ka != *kb) {
          throw PoseError("poses_a holds " + std::to_string(*ka) + " poses and poses_b " +
                          std::to_string(*kb) + "; expected the same count (or one pose)");
        }
        const std::size_t k = ka ? *ka : kb ? *kb : 1;  // one pose on both sides: one query
        const std::vector<Pose> pa = posesFrom(posesA, "poses_a", k);
        const std::vector<Pose> pb = posesFrom(posesB, "poses_b", k);
        Batch batch;
        {
          py::gil_scoped_release release;
          batch = collideBatch(*a, pa, *b, pb, settings, static_cast<int>(threads));
        }
        return batchArrays(batch);
      },
      py::arg("tree_a").none(false), py::arg("poses_a"), py::arg("tree_b").none(false),
      py::arg("poses_b"),
      ADB_QUERY_KWARGS, py::arg("threads") = 1,
      "collide() over K pose pairs: poses_a and poses_b are (K, 4, 4) or (K, 3, 4) arrays, or "
      "one pose for all K. Runs without the GIL on `threads` threads (0: all hardware "
      "threads); the answers do not depend on the count (but for time budgets). Returns a "
      "dict of arrays of length K: 'collides' (bool), 'confidence', 'stop' (str), "
      "'node_pairs', 'triangle_tests', 'seconds' and 'witness' (K, 2): the mesh triangles of "
      "the first intersecting pair, -1 where none.");
}

}  // namespace adb::python
