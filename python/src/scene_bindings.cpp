// adb.Scene: a scene file, JSON text, a dict (a scene built in Python, meshes given in
// memory), or the pile made in code; its world settings adjustable before a World is built.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "adb/core/errors.h"
#include "adb/scene/pile_scene.h"
#include "adb/scene/scene_file.h"
#include "bindings.h"
#include "settings.h"

namespace adb::python {
namespace {

using scene::Scene;
/// Python's dict of meshes given in code, by shape name.
using MeshMap = std::map<std::string, std::shared_ptr<TriangleMesh>>;

scene::GivenMeshes givenMeshes(const MeshMap& m) {
  scene::GivenMeshes out;
  for (const auto& [name, mesh] : m) {
    if (!mesh) throw MeshError("meshes['" + name + "']: None, expected an adb.Mesh");
    out[name] = mesh;
  }
  return out;
}

scene::PileSpec::Floor floorFrom(const std::string& name) {
  if (name == "mesh") return scene::PileSpec::Floor::Mesh;
  if (name == "box") return scene::PileSpec::Floor::Box;
  if (name == "plane") return scene::PileSpec::Floor::Plane;
  throw SettingsError("floor: '" + name + "', expected 'mesh', 'box' or 'plane'");
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
             const MeshMap& meshes) {
            return scene::parseScene(text, "<json>", folder, givenMeshes(meshes));
          },
          py::arg("text"), py::kw_only(), py::arg("folder") = std::filesystem::path("."),
          py::arg("meshes") = MeshMap{},
          "A scene from JSON text; `folder` resolves mesh files, and a 'mesh' shape without a "
          "'file' takes the adb.Mesh `meshes` holds under its name.")
      .def_static(
          "from_dict",
          [](const py::dict& d, const std::filesystem::path& folder,
             const MeshMap& meshes) {
            // numpy arrays and scalars (positions, quaternions) are written as their lists.
            const py::cpp_function asList([](const py::handle& value) -> py::object {
              if (py::hasattr(value, "tolist")) return value.attr("tolist")();
              throw scene::SceneError(
                  "<dict>", "",
                  "a " + py::str(py::type::of(value).attr("__name__")).cast<std::string>() +
                      " is not a value a scene holds (numbers, strings, lists, dicts)");
            });
            const std::string text = py::module_::import("json")
                                         .attr("dumps")(d, py::arg("default") = asList)
                                         .cast<std::string>();
            return scene::parseScene(text, "<dict>", folder, givenMeshes(meshes));
          },
          py::arg("scene"), py::kw_only(), py::arg("folder") = std::filesystem::path("."),
          py::arg("meshes") = MeshMap{},
          "A scene from a dict of the scene file's schema (a scene built in Python). A 'mesh' "
          "shape without a 'file' takes the adb.Mesh `meshes` holds under its name.")
      .def_static(
          "pile",
          [](int bodies, long long triangles, long long seed, const std::string& floor,
             int steps, const std::vector<std::filesystem::path>& meshes,
             const std::string& model, bool sleeping) {
            requireRange(bodies, 1, 100000, "bodies");
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
            spec.model = model;
            spec.sleeping = sleeping;
            try {
              return scene::makePileScene(spec);
            } catch (const MeshError& e) {  // an unknown model name: a setting, named
              throw SettingsError(std::string("model: ") + e.what());
            }
          },
          py::kw_only(), py::arg("bodies") = 24, py::arg("triangles") = 1500,
          py::arg("seed") = 1, py::arg("floor") = "mesh", py::arg("steps") = 300,
          py::arg("meshes") = std::vector<std::filesystem::path>{}, py::arg("model") = "",
          py::arg("sleeping") = true,
          "adb-demo's pile: concave bodies (generated tori, gears and knots of about "
          "`triangles` triangles, copies of the generated `model` (adb.model's names), or "
          "copies of the mesh files `meshes`) dropped into a bin whose floor is box meshes "
          "('mesh'), btBoxShape ('box') or a plane ('plane'). Bodies fall asleep as Bullet's "
          "deactivation decides unless `sleeping` is False.")
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

}  // namespace

void bindScenes(py::module_& m) { bindScene(m); }

}  // namespace adb::python
