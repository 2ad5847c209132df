// adb.Scene (a scene file, JSON text, a dict, or the pile made in code) and adb.World (the
// scene built into a Bullet world by adb::scene, stepped without the GIL, read back as numpy
// arrays, and drawn to a PNG).
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "adb/core/errors.h"
#include "adb/scene/pile_scene.h"
#include "adb/scene/recorder.h"
#include "adb/scene/scene_file.h"
#include "adb/scene/scene_world.h"
#include "arrays.h"
#include "bindings.h"
#include "render/png_file.h"
#include "render/scene_picture.h"
#include "scene_run/convex_peer.h"

namespace adb::python {
namespace {

using scene::Scene;

scene::GivenMeshes givenMeshes(const std::map<std::string, std::shared_ptr<TriangleMesh>>& m) {
  scene::GivenMeshes out;
  for (const auto& [name, mesh] : m) out[name] = mesh;
  return out;
}

scene::PileSpec::Floor floorFrom(const std::string& name) {
  if (name == "mesh") return scene::PileSpec::Floor::Mesh;
  if (name == "box") return scene::PileSpec::Floor::Box;
  if (name == "plane") return scene::PileSpec::Floor::Plane;
  throw SettingsError("floor: '" + name + "', expected 'mesh', 'box' or 'plane'");
}

scene::Backend backendFrom(const std::string& name) {
  try {
    return scene::parseBackend(name);
  } catch (const std::invalid_argument& e) {
    throw SettingsError(std::string("backend: ") + e.what());
  }
}

void requireRange(double value, double lo, double hi, const char* name) {
  if (!(value >= lo && value <= hi)) {
    throw SettingsError(std::string(name) + ": " + std::to_string(value) + ", expected " +
                        std::to_string(lo) + " to " + std::to_string(hi));
  }
}

void bindScene(py::module_& m) {
  py::class_<Scene>(m, "Scene",
                    "A scene: the world's settings, shapes, bodies, motions and the effects to "
                    "simulate (the schema: docs/scenes.md). Made by Scene.load, "
                    "Scene.from_json, Scene.from_dict or Scene.pile.")
      .def_static(
          "load", [](const std::filesystem::path& path) { return scene::loadScene(path); },
          py::arg("path"),
          "Reads and validates a scene file. Raises SceneError naming the file, where in it "
          "and what is wrong.")
      .def_static(
          "from_json",
          [](const std::string& text, const std::filesystem::path& folder,
             const std::map<std::string, std::shared_ptr<TriangleMesh>>& meshes) {
            return scene::parseScene(text, "<json>", folder, givenMeshes(meshes));
          },
          py::arg("text"), py::kw_only(), py::arg("folder") = std::filesystem::path("."),
          py::arg("meshes") = std::map<std::string, std::shared_ptr<TriangleMesh>>{},
          "A scene from JSON text; `folder` resolves mesh files, and a 'mesh' shape without a "
          "'file' takes the adb.Mesh `meshes` holds under its name.")
      .def_static(
          "from_dict",
          [](const py::dict& d, const std::filesystem::path& folder,
             const std::map<std::string, std::shared_ptr<TriangleMesh>>& meshes) {
            const std::string text =
                py::module_::import("json").attr("dumps")(d).cast<std::string>();
            return scene::parseScene(text, "<dict>", folder, givenMeshes(meshes));
          },
          py::arg("scene"), py::kw_only(), py::arg("folder") = std::filesystem::path("."),
          py::arg("meshes") = std::map<std::string, std::shared_ptr<TriangleMesh>>{},
          "A scene from a dict of the scene file's schema (a scene built in Python). A 'mesh' "
          "shape without a 'file' takes the adb.Mesh `meshes` holds under its name.")
      .def_static(
          "pile",
          [](int bodies, long long triangles, long long seed, const std::string& floor,
             int steps, const std::vector<std::filesystem::path>& meshes) {
            if (bodies < 1 || bodies > 100000) {
              throw SettingsError("bodies: " + std::to_string(bodies) + ", expected 1 to 100000");
            }
            requireRange(static_cast<double>(triangles), 12, 1e7, "triangles");
            requireRange(static_cast<double>(seed), 0, 9e18, "seed");
            requireRange(steps, 1, 1e8, "steps");
            scene::PileSpec spec;
            spec.bodies = bodies;
            spec.trianglesPerBody = static_cast<std::size_t>(triangles);
            spec.seed = static_cast<std::uint64_t>(seed);
            spec.floor = floorFrom(floor);
            spec.steps = steps;
            spec.meshes = meshes;
            return scene::makePileScene(spec);
          },
          py::kw_only(), py::arg("bodies") = 24, py::arg("triangles") = 1500,
          py::arg("seed") = 1, py::arg("floor") = "mesh", py::arg("steps") = 300,
          py::arg("meshes") = std::vector<std::filesystem::path>{},
          "adb-demo's pile: concave bodies (generated tori, gears and knots of about "
          "`triangles` triangles, or copies of the mesh files `meshes`) dropped into a bin "
          "whose floor is box meshes ('mesh'), btBoxShape ('box') or a plane ('plane').")
      .def_property_readonly(
          "description", [](const Scene& s) { return s.description; }, "The scene's description.")
      .def_property_readonly("body_names",
                             [](const Scene& s) {
                               std::vector<std::string> names;
                               for (const auto& b : s.bodies) names.push_back(b.name);
                               return names;
                             },
                             "The bodies' names, in the order of poses() and body indices.")
      .def_property_readonly(
          "time_step", [](const Scene& s) { return s.world.timeStep; }, "Seconds a step.")
      .def_property(
          "steps", [](const Scene& s) { return s.world.steps; },
          [](Scene& s, int steps) {
            requireRange(steps, 1, 1e8, "steps");
            s.world.steps = steps;
          },
          "Steps a run takes (world.steps).")
      .def_property(
          "threads", [](const Scene& s) { return s.world.threads; },
          [](Scene& s, int threads) {
            requireRange(threads, 0, 4096, "threads");
            s.world.threads = threads;
          },
          "Threads for adb's pair queries (world.threads): 0 all, 1 none.")
      .def_property(
          "budget_us",
          [](const Scene& s) -> std::optional<double> {
            if (s.world.budget.kind != scene::BudgetSpec::Kind::Micros) return std::nullopt;
            return s.world.budget.micros;
          },
          [](Scene& s, std::optional<double> micros) {
            if (!micros) {
              if (s.world.budget.kind == scene::BudgetSpec::Kind::Micros) s.world.budget = {};
              return;
            }
            requireRange(*micros, 0.0, 1e12, "budget_us");
            s.world.budget = {scene::BudgetSpec::Kind::Micros, *micros, 0};
          },
          "The per-step time budget in microseconds, or None (setting it replaces a "
          "node-pair budget).")
      .def_property(
          "budget_pairs",
          [](const Scene& s) -> std::optional<std::uint64_t> {
            if (s.world.budget.kind != scene::BudgetSpec::Kind::NodePairs) return std::nullopt;
            return s.world.budget.nodePairs;
          },
          [](Scene& s, std::optional<long long> pairs) {
            if (!pairs) {
              if (s.world.budget.kind == scene::BudgetSpec::Kind::NodePairs) s.world.budget = {};
              return;
            }
            requireRange(static_cast<double>(*pairs), 1.0, 9e18, "budget_pairs");
            s.world.budget = {scene::BudgetSpec::Kind::NodePairs, 0.0,
                              static_cast<std::uint64_t>(*pairs)};
          },
          "The per-step node-pair budget (reproducible at any thread count), or None.")
      .def("__repr__", [](const Scene& s) {
        return "<adb.Scene " + std::to_string(s.bodies.size()) + " bodies, " +
               std::to_string(s.world.steps) + " steps: " + s.description + ">";
      });
}

/// A scene built and stepped, with its steps.csv rows kept for stats().
class World {
 public:
  World(const Scene& scene, scene::Backend backend, std::optional<int> threads,
        const std::optional<std::filesystem::path>& out) {
    Scene s = scene;
    if (threads) {
      requireRange(*threads, 0, 4096, "threads");
      s.world.threads = *threads;
    }
    m_world = std::make_unique<scene::SceneWorld>(std::move(s), backend,
                                                  demo::convexShapeMaker(m_decomposition));
    m_recorder = out ? std::make_unique<scene::Recorder>(*m_world, *out)
                     : std::make_unique<scene::Recorder>(*m_world);
  }

  // n steps without the GIL, taking it back between steps only to see a Ctrl-C.
  void step(long long n) {
    if (n < 0) throw SettingsError("n: " + std::to_string(n) + ", expected steps >= 0");
    py::gil_scoped_release release;
    for (long long i = 0; i < n; ++i) {
      m_world->step();
      m_recorder->record(*m_world);
      for (const scene::StepCell& cell : scene::stepCells(m_world->last())) {
        m_rows.push_back(cell.value);
      }
      const auto& events = m_world->events();
      m_events.insert(m_events.end(), events.begin(), events.end());
      py::gil_scoped_acquire acquire;
      if (PyErr_CheckSignals() != 0) {
        m_recorder->flush();
        throw py::error_already_set();
      }
    }
    m_recorder->flush();
  }

  py::dict stats() const {
    const std::size_t steps = m_rows.size() / scene::kStepColumns;
    const auto cells = scene::stepCells(scene::StepRecord{});
    py::dict d;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      if (cells[c].integer) {
        py::array_t<std::int64_t> a = newArray<std::int64_t>({static_cast<py::ssize_t>(steps)});
        for (std::size_t i = 0; i < steps; ++i) {
          a.mutable_at(static_cast<py::ssize_t>(i)) =
              static_cast<std::int64_t>(m_rows[i * scene::kStepColumns + c]);
        }
        d[cells[c].column] = a;
      } else {
        py::array_t<double> a = newArray<double>({static_cast<py::ssize_t>(steps)});
        for (std::size_t i = 0; i < steps; ++i) {
          a.mutable_at(static_cast<py::ssize_t>(i)) = m_rows[i * scene::kStepColumns + c];
        }
        d[cells[c].column] = a;
      }
    }
    return d;
  }

  py::array_t<double> poses() const {
    std::vector<Pose> poses(m_world->bodyCount());
    for (std::size_t i = 0; i < poses.size(); ++i) poses[i] = m_world->scenePose(i);
    return poseArrays(poses);
  }

  py::dict contacts() const {
    const auto& points = m_world->contacts();
    const auto n = static_cast<py::ssize_t>(points.size());
    py::array_t<double> position = newArray<double>({n, 3});
    py::array_t<double> depth = newArray<double>({n});
    py::array_t<double> confidence = newArray<double>({n});
    py::array_t<std::int64_t> bodies = newArray<std::int64_t>({n, 2});
    for (py::ssize_t i = 0; i < n; ++i) {
      const scene::ContactPoint& p = points[static_cast<std::size_t>(i)];
      for (int k = 0; k < 3; ++k) position.mutable_at(i, k) = p.position[k];
      depth.mutable_at(i) = p.depth;
      confidence.mutable_at(i) = p.confidence;
      bodies.mutable_at(i, 0) = p.body0;
      bodies.mutable_at(i, 1) = p.body1;
    }
    py::dict d;
    d["position"] = position;
    d["depth"] = depth;
    d["confidence"] = confidence;
    d["bodies"] = bodies;
    return d;
  }

  py::dict events() const {
    const auto n = static_cast<py::ssize_t>(m_events.size());
    py::array_t<std::int64_t> step = newArray<std::int64_t>({n});
    py::array_t<double> time = newArray<double>({n});
    py::array_t<bool> begin = newArray<bool>({n});
    py::dict d = pairArrays(m_events);
    for (py::ssize_t i = 0; i < n; ++i) {
      const scene::OverlapEvent& e = m_events[static_cast<std::size_t>(i)];
      step.mutable_at(i) = e.step;
      time.mutable_at(i) = e.time;
      begin.mutable_at(i) = e.begin;
    }
    d["step"] = step;
    d["time"] = time;
    d["begin"] = begin;
    return d;
  }

  template <class Pair>
  static py::dict pairArrays(const std::vector<Pair>& pairs) {
    const auto n = static_cast<py::ssize_t>(pairs.size());
    py::array_t<std::int64_t> bodies = newArray<std::int64_t>({n, 2});
    py::array_t<double> confidence = newArray<double>({n});
    for (py::ssize_t i = 0; i < n; ++i) {
      bodies.mutable_at(i, 0) = pairs[static_cast<std::size_t>(i)].body0;
      bodies.mutable_at(i, 1) = pairs[static_cast<std::size_t>(i)].body1;
      confidence.mutable_at(i) = pairs[static_cast<std::size_t>(i)].confidence;
    }
    py::dict d;
    d["bodies"] = bodies;
    d["confidence"] = confidence;
    return d;
  }

  void render(const std::filesystem::path& path, int width, int height) const {
    requireRange(width, 16, 16384, "width");
    requireRange(height, 16, 16384, "height");
    py::gil_scoped_release release;
    const render::Image image = demo::drawScene(*m_world, demo::sceneCamera(*m_world), width,
                                                height, demo::sceneCaption(*m_world));
    render::writePng(image, path);
  }

  py::dict summary() {
    const scene::RunSummary& s = m_recorder->finish();
    py::dict d;
    d["backend"] = s.backend;
    d["effects"] = s.effects;
    d["world"] = s.world;
    d["steps"] = s.steps;
    d["bodies"] = s.bodies;
    d["triangles"] = s.triangles;
    d["build_seconds"] = s.buildSeconds;
    d["mean_step_ms"] = s.meanStepMillis;
    d["p99_step_ms"] = s.p99StepMillis;
    d["max_step_ms"] = s.maxStepMillis;
    d["mean_pair_ms"] = s.meanPairMillis;
    d["mean_budget_use"] = s.meanBudgetUse;
    d["mean_confidence"] = s.meanConfidence;
    d["worst_confidence"] = s.worstConfidence;
    d["max_penetration"] = s.maxPenetration;
    d["most_lost"] = s.mostLost;
    d["at_rest_at_end"] = s.atRestAtEnd;
    d["dynamic_bodies"] = s.dynamicBodies;
    return d;
  }

  const scene::SceneWorld& world() const { return *m_world; }

 private:
  demo::DecompositionReport m_decomposition;  // outlives the world, whose maker fills it
  std::unique_ptr<scene::SceneWorld> m_world;
  std::unique_ptr<scene::Recorder> m_recorder;
  std::vector<double> m_rows;  // kStepColumns values per step
  std::vector<scene::OverlapEvent> m_events;  // every step's, in order
};

void bindWorld(py::module_& m) {
  py::class_<World>(m, "World",
                    "A scene built into a Bullet world with only what its effects ask for.")
      .def(py::init([](const Scene& scene, const std::string& backend,
                       std::optional<int> threads,
                       const std::optional<std::filesystem::path>& out) {
             const scene::Backend b = backendFrom(backend);
             py::gil_scoped_release release;
             return std::make_unique<World>(scene, b, threads, out);
           }),
           py::arg("scene"), py::kw_only(), py::arg("backend") = "adb",
           py::arg("threads") = py::none(), py::arg("out") = py::none(),
           "Builds the world (reads and generates meshes, builds trees and shapes). backend: "
           "'adb' (the scene's budget), 'exact' (adb without a budget), 'gimpact' (Bullet's) "
           "or 'convex' (Bullet's HACD hulls). threads overrides world.threads. out: a folder "
           "to write steps.csv (and summary.json on summary()) into, as adb-demo does.")
      .def("step", &World::step, py::arg("n") = 1,
           "Advances n steps (the GIL released; Ctrl-C stops between steps).")
      .def("poses", &World::poses,
           "(B, 4, 4): each body's pose in the scene's terms (its mesh's own frame).")
      .def("stats", &World::stats,
           "Every step so far as the columns of steps.csv (docs/scenes.md): a dict of arrays, "
           "int64 for counts, float64 otherwise.")
      .def("contacts", &World::contacts,
           "Contact points after the last step: a dict of 'position' (N, 3, world), 'depth' "
           "(N,), 'confidence' (N,, 1 for exact) and 'bodies' (N, 2) body indices.")
      .def("cut_pairs", [](const World& w) { return World::pairArrays(w.world().cutPairs()); },
           "Pairs a budget cut in the last step: 'bodies' (N, 2) and 'confidence' (N,).")
      .def("overlapping",
           [](const World& w) { return World::pairArrays(w.world().overlapping()); },
           "Overlap scenes: the pairs overlapping after the last step.")
      .def("events", &World::events,
           "Overlap scenes: every begin and end event so far, as arrays: 'step', 'time', "
           "'begin' (False: the pair stopped overlapping), 'bodies' (N, 2) and 'confidence' "
           "(that the pair's answer that step is right).")
      .def("render", &World::render, py::arg("path"), py::kw_only(), py::arg("width") = 640,
           py::arg("height") = 480,
           "Draws the world as it is now to a PNG: bodies shaded, contact points and cut pairs "
           "coloured by confidence, a caption.")
      .def("summary", &World::summary, "The run in figures, as adb-demo's summary.json.")
      .def_property_readonly("body_names",
                             [](const World& w) {
                               std::vector<std::string> names;
                               for (const auto& b : w.world().scene().bodies) names.push_back(b.name);
                               return names;
                             },
                             "The bodies' names, in the order of poses() and body indices.")
      .def_property_readonly("backend",
                             [](const World& w) { return std::string(toString(w.world().backend())); },
                             "'adb', 'exact', 'gimpact' or 'convex'.")
      .def_property_readonly("built", [](const World& w) { return w.world().built().describe(); },
                             "What was built: the world, the solver, contacts or queries.")
      .def_property_readonly(
          "step_count", [](const World& w) { return w.world().last().step; }, "Steps taken.")
      .def_property_readonly(
          "time", [](const World& w) { return w.world().last().time; }, "Simulated seconds.");
}

}  // namespace

void bindScenes(py::module_& m) {
  bindScene(m);
  bindWorld(m);
}

}  // namespace adb::python
