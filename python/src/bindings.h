// The parts of the Python module adb._adb, each registered by its own function (module.cpp
// calls them in order: errors first, so that every later part's errors have their types).
#pragma once

#include <pybind11/pybind11.h>

namespace adb::python {

namespace py = pybind11;

void bindErrors(py::module_& m);
void bindMeshes(py::module_& m);
void bindQueries(py::module_& m);
void bindScenes(py::module_& m);
void bindWorlds(py::module_& m);

}  // namespace adb::python
