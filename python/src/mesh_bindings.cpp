// adb.Mesh, adb.Tree, adb.load_mesh and the generated models.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <filesystem>

#include <memory>
#include <string>

#include "adb/core/errors.h"
#include "adb/core/tree.h"
#include "adb/io/mesh_file.h"
#include "adb/support/mesh_generators.h"
#include "arrays.h"
#include "bindings.h"
#include "settings.h"

namespace adb::python {
namespace {

using MeshPtr = std::shared_ptr<TriangleMesh>;

py::array_t<double> vertexArray(const TriangleMesh& mesh) {
  const auto& v = mesh.vertices();
  py::array_t<double> out = newArray<double>({static_cast<py::ssize_t>(v.size()), 3});
  double* p = out.mutable_data();
  for (std::size_t i = 0; i < v.size(); ++i) {
    for (int c = 0; c < 3; ++c) p[3 * i + c] = v[i][c];
  }
  return out;
}

py::array_t<std::int64_t> triangleArray(const TriangleMesh& mesh) {
  const auto& t = mesh.triangles();
  py::array_t<std::int64_t> out = newArray<std::int64_t>({static_cast<py::ssize_t>(t.size()), 3});
  std::int64_t* p = out.mutable_data();
  for (std::size_t i = 0; i < t.size(); ++i) {
    for (int c = 0; c < 3; ++c) p[3 * i + c] = t[i][c];
  }
  return out;
}

CellCounting countingFrom(const std::string& name) {
  if (name == "approximate") return CellCounting::Approximate;
  if (name == "exact") return CellCounting::Exact;
  throw SettingsError("counting: '" + name + "', expected 'approximate' or 'exact'");
}

void bindMesh(py::module_& m) {
  py::class_<TriangleMesh, MeshPtr>(m, "Mesh",
                                    "An indexed triangle mesh, validated once when made.")
      .def(py::init([](const py::handle& vertices, const py::handle& triangles,
                       const std::string& name) {
             return std::make_shared<TriangleMesh>(meshFrom(vertices, triangles, name));
           }),
           py::arg("vertices"), py::arg("triangles"), py::arg("name") = "mesh",
           "A mesh from a (N, 3) array of vertex coordinates and a (M, 3) array of vertex "
           "indices. Raises MeshError naming a wrong shape or dtype, a non-finite coordinate "
           "(its vertex), an index out of range (its triangle) or an empty mesh. Degenerate "
           "triangles are legal (counted in `report`).")
      .def_property_readonly("vertices", &vertexArray, "(N, 3) float64 copy of the vertices.")
      .def_property_readonly("triangles", &triangleArray, "(M, 3) int64 copy of the indices.")
      .def_property_readonly("triangle_count", &TriangleMesh::triangleCount, "Triangles (M).")
      .def_property_readonly(
          "vertex_count", [](const TriangleMesh& mesh) { return mesh.vertices().size(); },
          "Vertices (N).")
      .def_property_readonly("name", &TriangleMesh::name, "Used in error messages.")
      .def_property_readonly(
          "bounds",
          [](const TriangleMesh& mesh) {
            py::array_t<double> out = newArray<double>({2, 3});
            for (int c = 0; c < 3; ++c) {
              out.mutable_at(0, c) = mesh.bounds().lo[c];
              out.mutable_at(1, c) = mesh.bounds().hi[c];
            }
            return out;
          },
          "(2, 3) array: the lower and upper corner of the bounding box.")
      .def_property_readonly(
          "report",
          [](const TriangleMesh& mesh) {
            py::dict d;
            d["degenerate_triangles"] = mesh.report().degenerateTriangles;
            d["repeated_vertex_triangles"] = mesh.report().repeatedVertexTriangles;
            d["unused_vertices"] = mesh.report().unusedVertices;
            return d;
          },
          "What validation found that is legal but worth knowing.")
      .def("__repr__", [](const TriangleMesh& mesh) {
        return "<adb.Mesh '" + mesh.name() + "': " + std::to_string(mesh.vertices().size()) +
               " vertices, " + std::to_string(mesh.triangleCount()) + " triangles>";
      });

  m.def(
      "load_mesh",
      [](const std::filesystem::path& path, bool isolate, double maxReadSeconds) {
        io::LoadLimits limits;
        limits.isolate = isolate;
        limits.maxReadSeconds = maxReadSeconds;
        py::gil_scoped_release release;
        return std::make_shared<TriangleMesh>(io::loadMesh(path.string(), nullptr, limits));
      },
      py::arg("path"), py::kw_only(), py::arg("isolate") = true,
      py::arg("max_read_seconds") = 20.0,
      "Reads any mesh file adb reads (OBJ, STL, PLY, OFF, glTF, 3MF, ... through assimp), "
      "triangulated and merged into one mesh. Formats read by assimp are read in a child "
      "process (isolate=True): a damaged file that would crash or hang the reader gives one "
      "MeshError naming the file. Raises MeshError for a missing, unreadable or empty file.");

  m.def("model_names", &gen::modelNames, "The generated models model() makes.");
  m.def(
      "model",
      [](const std::string& name, long long triangles) {
        requireRange(static_cast<double>(triangles), 12, 1e7, "triangles");
        py::gil_scoped_release release;
        return std::make_shared<TriangleMesh>(
            gen::makeModel(name, static_cast<std::size_t>(triangles)));
      },
      py::arg("name"), py::arg("triangles") = 2000,
      "A generated benchmark model (model_names()) of about `triangles` triangles, about 2 "
      "units across: the same mesh on every machine. Raises MeshError for an unknown name.");
}

void bindTree(py::module_& m) {
  py::class_<AdbTree, std::shared_ptr<AdbTree>>(
      m, "Tree",
      "The ADB-tree of a mesh: a bounding-volume hierarchy whose nodes also store how their "
      "triangles are distributed. Immutable: any number of threads may query it at once.")
      .def(py::init([](const TriangleMesh& mesh, long long gridResolution,
                       long long maxLeafTriangles, const std::string& counting,
                       double areaThreshold) {
             BuildSettings s;
             requireRange(static_cast<double>(gridResolution), 1, 32, "grid_resolution");
             requireRange(static_cast<double>(maxLeafTriangles), 1, 15, "max_leaf_triangles");
             s.gridResolution = static_cast<int>(gridResolution);
             s.maxLeafTriangles = static_cast<int>(maxLeafTriangles);
             s.counting = countingFrom(counting);
             s.areaThreshold = areaThreshold;
             py::gil_scoped_release release;
             return std::make_shared<AdbTree>(mesh, s);
           }),
           py::arg("mesh"), py::kw_only(), py::arg("grid_resolution") = 8,
           py::arg("max_leaf_triangles") = 4, py::arg("counting") = "approximate",
           py::arg("area_threshold") = 0.35,
           "Builds the tree of `mesh`. grid_resolution: cells per axis of each node's grid "
           "(1..32; the paper's 8); max_leaf_triangles: 1..15; counting: 'approximate' (the "
           "paper's Fig. 5) or 'exact' (clip every triangle, slower); area_threshold in (0, 1]: "
           "the share of a cell's largest polygon area that makes it a possible collision "
           "cell. Raises SettingsError for a value out of range, MeshError for a mesh too "
           "large or too small for float boxes.")
      .def_property_readonly("triangle_count", &AdbTree::triangleCount, "Triangles of the mesh.")
      .def_property_readonly(
          "node_count", [](const AdbTree& t) { return t.nodes().size(); }, "Nodes of the tree.")
      .def_property_readonly("max_depth", &AdbTree::maxDepth, "Depth of the deepest leaf.")
      .def_property_readonly("memory_bytes", &AdbTree::memoryBytes,
                             "Bytes held by the tree's arrays.")
      .def_property_readonly(
          "build_seconds",
          [](const AdbTree& t) { return t.hierarchySeconds() + t.countingSeconds(); },
          "Wall clock of the build: hierarchy and cell counts.")
      .def("__repr__", [](const AdbTree& t) {
        return "<adb.Tree: " + std::to_string(t.triangleCount()) + " triangles, " +
               std::to_string(t.nodes().size()) + " nodes, depth " +
               std::to_string(t.maxDepth()) + ">";
      });
}

}  // namespace

void bindMeshes(py::module_& m) {
  bindMesh(m);
  bindTree(m);
}

}  // namespace adb::python
