// adb's errors as Python exceptions: MeshError, SceneError, SettingsError and PoseError, each a
// ValueError carrying the C++ message unchanged. The io and scene layers' file errors map onto
// them (a mesh file that cannot be read is a MeshError, a bad scene a SceneError).
#include <exception>

#include "adb/core/errors.h"
#include "adb/io/mesh_file.h"
#include "adb/scene/scene_file.h"
#include "bindings.h"

namespace adb::python {
namespace {

// The Python types, created once by bindErrors (the module lives as long as the interpreter).
PyObject* g_meshError = nullptr;
PyObject* g_sceneError = nullptr;
PyObject* g_settingsError = nullptr;
PyObject* g_poseError = nullptr;

PyObject* newError(py::module_& m, const char* name, const char* doc) {
  const std::string qualified = std::string("adb.") + name;
  PyObject* type = PyErr_NewExceptionWithDoc(qualified.c_str(), doc, PyExc_ValueError, nullptr);
  if (type == nullptr) throw py::error_already_set();
  m.add_object(name, py::handle(type));  // the module keeps a reference
  return type;
}

}  // namespace

void bindErrors(py::module_& m) {
  struct ErrorType {
    PyObject** type;
    const char* name;
    const char* doc;
  };
  const ErrorType types[] = {
      {&g_meshError, "MeshError",
       "A bad mesh: an array of the wrong shape or type, a non-finite coordinate, a bad index, "
       "no triangles, or a file that cannot be read."},
      {&g_sceneError, "SceneError",
       "A bad scene: the file, where in it (a JSON path or line and column) and what is wrong."},
      {&g_settingsError, "SettingsError",
       "A setting out of range (p_min, k_min, a budget, a backend, ...), named with its range."},
      {&g_poseError, "PoseError",
       "A bad pose: wrong shape or type, a non-finite entry, a last row other than "
       "[0, 0, 0, 1], or a rotation that is not orthonormal."},
  };
  for (const ErrorType& t : types) *t.type = newError(m, t.name, t.doc);
  // Tried before pybind11's own translators: adb's error types and the layers' file errors;
  // anything else goes on to pybind11's (std::invalid_argument as ValueError, ...).
  py::register_exception_translator([](std::exception_ptr error) {
    try {
      if (error) std::rethrow_exception(error);
    } catch (const adb::MeshError& e) {
      PyErr_SetString(g_meshError, e.what());
    } catch (const adb::io::MeshFileError& e) {
      PyErr_SetString(g_meshError, e.what());
    } catch (const adb::scene::SceneError& e) {
      PyErr_SetString(g_sceneError, e.what());
    } catch (const adb::SettingsError& e) {
      PyErr_SetString(g_settingsError, e.what());
    } catch (const adb::PoseError& e) {
      PyErr_SetString(g_poseError, e.what());
    }
  });
}

}  // namespace adb::python
