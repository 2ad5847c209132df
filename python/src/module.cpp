// adb._adb: the compiled part of the Python package adb (python/adb/__init__.py re-exports it
// with the pure-Python CollisionManager). docs/python.md is its guide.
#include "bindings.h"

PYBIND11_MODULE(_adb, m) {
  m.doc() =
      "adb: collision queries between concave triangle meshes under a time or work budget, "
      "with the probability that each answer is right (ADB-trees), and Bullet scenes "
      "simulated with them.";
  adb::python::bindErrors(m);
  adb::python::bindMeshes(m);
  adb::python::bindQueries(m);
  adb::python::bindScenes(m);
  adb::python::bindWorlds(m);
}
