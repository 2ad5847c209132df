// adb.World: a scene built into a Bullet world by adb::scene (the one world builder), stepped
// without the GIL, read back as numpy arrays (the columns of steps.csv, poses, contacts,
// events) and drawn to a PNG.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "adb/core/errors.h"
#include "adb/scene/recorder.h"
#include "adb/scene/scene_world.h"
#include "arrays.h"
#include "scene_arrays.h"
#include "bindings.h"
#include "render/png_file.h"
#include "render/scene_picture.h"
#include "scene_run/convex_peer.h"
#include "settings.h"

namespace adb::python {
namespace {

using scene::Scene;

scene::Backend backendFrom(const std::string& name) {
  try {
    return scene::parseBackend(name);
  } catch (const std::invalid_argument& e) {
    throw SettingsError(std::string("backend: ") + e.what());
  }
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

  py::array_t<double> poses() const {
    std::vector<Pose> poses(m_world->bodyCount());
    for (std::size_t i = 0; i < poses.size(); ++i) poses[i] = m_world->scenePose(i);
    return poseArrays(poses);
  }

  void render(const std::filesystem::path& path, int width, int height) const {
    requireRange(width, 16, 16384, "width");
    requireRange(height, 16, 16384, "height");
    py::gil_scoped_release release;
    const double meanStep = m_recorder->meanStepMillisSoFar();
    const render::Image image = demo::drawScene(*m_world, demo::sceneCamera(*m_world), width,
                                                height, demo::sceneCaption(*m_world, meanStep));
    render::writePng(image, path);
  }

  const scene::SceneWorld& world() const { return *m_world; }
  const std::vector<double>& rows() const { return m_rows; }
  const std::vector<scene::OverlapEvent>& events() const { return m_events; }
  const scene::RunSummary& finish() { return m_recorder->finish(); }

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
      .def("stats", [](const World& w) { return stepArrays(w.rows()); },
           "Every step so far as the columns of steps.csv (docs/scenes.md): a dict of arrays, "
           "int64 for counts, float64 otherwise.")
      .def("contacts", [](const World& w) { return contactArrays(w.world().contacts()); },
           "Contact points after the last step: a dict of 'position' (N, 3, world), 'depth' "
           "(N,), 'confidence' (N,, 1 for exact) and 'bodies' (N, 2) body indices.")
      .def("cut_pairs", [](const World& w) { return pairArrays(w.world().cutPairs()); },
           "Pairs a budget cut in the last step: 'bodies' (N, 2) and 'confidence' (N,).")
      .def("overlapping",
           [](const World& w) { return pairArrays(w.world().overlapping()); },
           "Overlap scenes: the pairs overlapping after the last step.")
      .def("events", [](const World& w) { return eventArrays(w.events()); },
           "Overlap scenes: every begin and end event so far, as arrays: 'step', 'time', "
           "'begin' (False: the pair stopped overlapping), 'bodies' (N, 2) and 'confidence' "
           "(that the pair's answer that step is right).")
      .def("render", &World::render, py::arg("path"), py::kw_only(), py::arg("width") = 640,
           py::arg("height") = 480,
           "Draws the world as it is now to a PNG: bodies shaded, contact points and cut pairs "
           "coloured by confidence, a caption.")
      .def("summary", [](World& w) { return summaryDict(w.finish()); }, "The run in figures, as adb-demo's summary.json.")
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

void bindWorlds(py::module_& m) { bindWorld(m); }

}  // namespace adb::python
