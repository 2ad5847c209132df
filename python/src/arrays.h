// numpy arrays in and out: every array an adb call takes is checked here, and a bad one is
// named with what is wrong (shape, dtype, a NaN, a pose that is not rigid) in the error of the
// layer it belongs to (MeshError for meshes, PoseError for poses).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <optional>
#include <string>
#include <vector>

#include "adb/core/geometry.h"
#include "adb/core/mesh.h"

namespace adb::python {

namespace py = pybind11;

/// A pose: a (4, 4) homogeneous matrix (last row [0, 0, 0, 1]) or its top (3, 4), of real
/// numbers, rigid (PoseDefect::None). `what` names the argument in errors.
Pose poseFrom(const py::handle& value, const std::string& what);

/// K poses: a (K, 4, 4) or (K, 3, 4) array (K may be 0), or a single pose standing for
/// `count` copies. Errors name the index: "poses_a[17]: ...".
std::vector<Pose> posesFrom(const py::handle& value, const std::string& what,
                            std::size_t count);
/// How many poses `value` holds: K for a (K, r, 4) array; none for a single pose.
std::optional<std::size_t> batchSize(const py::handle& value, const std::string& what);

/// A mesh from a (N, 3) array of real vertices and a (M, 3) array of integer indices.
TriangleMesh meshFrom(const py::handle& vertices, const py::handle& triangles,
                      const std::string& name);

/// Poses from (K, 4) quaternions [w, x, y, z] and (K, 3) translations, as
/// Pose::fromQuaternion makes them. Raises PoseError naming a wrong shape, dtype or a
/// non-finite or zero quaternion.
std::vector<Pose> posesFromQuaternions(const py::handle& quaternions,
                                       const py::handle& translations);
/// A 1-d array of real numbers (SettingsError naming `what` otherwise).
std::vector<double> realsFrom(const py::handle& values, const std::string& what);

/// (4, 4) and (B, 4, 4) arrays of poses.
py::array_t<double> poseArray(const Pose& pose);
py::array_t<double> poseArrays(const std::vector<Pose>& poses);

/// A new C-ordered array of the given shape.
template <class T>
py::array_t<T> newArray(std::vector<py::ssize_t> shape) {
  return py::array_t<T>(std::move(shape));
}

}  // namespace adb::python
