#include "arrays.h"

#include <cmath>
#include <cstdint>
#include <sstream>

#include "adb/core/errors.h"
#include "adb/core/query.h"

namespace adb::python {
namespace {

// What a pose's fourth row may differ from [0, 0, 0, 1] by: rounding of a product of poses.
constexpr double kLastRowTolerance = 1e-9;

std::string shapeText(const py::array& a) {
  std::ostringstream s;
  s << '(';
  for (py::ssize_t i = 0; i < a.ndim(); ++i) s << (i ? ", " : "") << a.shape(i);
  s << (a.ndim() == 1 ? ",)" : ")");
  return s.str();
}

std::string dtypeText(const py::array& a) { return py::str(a.dtype()).cast<std::string>(); }

// Any array-like as an array; a value numpy cannot read as one (a string, an object that is
// no sequence) is named.
template <class Error>
py::array checkedArray(const py::handle& value, const std::string& what) {
  if (!py::isinstance<py::str>(value) && !py::isinstance<py::bytes>(value)) {
    try {
      py::array a = py::array::ensure(value);
      if (a && a.dtype().kind() != 'O') return a;
    } catch (const py::error_already_set&) {
    }
  }
  throw Error(what + ": expected an array, got " +
              py::str(py::type::of(value).attr("__name__")).cast<std::string>());
}

bool isReal(const py::array& a) {
  const char kind = a.dtype().kind();
  return kind == 'f' || kind == 'i' || kind == 'u';
}

bool isInteger(const py::array& a) {
  const char kind = a.dtype().kind();
  return kind == 'i' || kind == 'u';
}

using Doubles = py::array_t<double, py::array::c_style | py::array::forcecast>;

// `what`, or what[index] for a pose of a batch: built only for an error message.
std::string poseName(const std::string& what, std::ptrdiff_t index) {
  return index < 0 ? what : what + "[" + std::to_string(index) + "]";
}

// The pose held by rows x 4 doubles at `p` (row-major), checked; `index` >= 0 names a pose of
// a batch.
Pose poseAt(const double* p, py::ssize_t rows, const std::string& what,
            std::ptrdiff_t index = -1) {
  for (py::ssize_t i = 0; i < rows * 4; ++i) {
    if (!std::isfinite(p[i])) {
      std::ostringstream s;
      s << poseName(what, index) << ": entry [" << i / 4 << ", " << i % 4 << "] is " << p[i]
        << "; a pose needs finite numbers";
      throw PoseError(s.str());
    }
  }
  if (rows == 4) {
    const double expected[4] = {0, 0, 0, 1};
    for (int j = 0; j < 4; ++j) {
      if (std::abs(p[12 + j] - expected[j]) > kLastRowTolerance) {
        throw PoseError(poseName(what, index) +
                        ": the last row of a 4x4 pose must be [0, 0, 0, 1]");
      }
    }
  }
  Pose pose;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) pose.rotation(r, c) = p[4 * r + c];
    pose.translation[r] = p[4 * r + 3];
  }
  const PoseDefect defect = poseDefect(pose);
  if (defect != PoseDefect::None) {
    throw PoseError(poseName(what, index) + ": " + describe(defect));
  }
  return pose;
}

// The poses' array as doubles, after checking its type and that its last two axes are (4, 4)
// or (3, 4); `batch`: a 3-d array (K poses) is allowed too.
Doubles poseDoubles(const py::handle& value, const std::string& what, bool batch) {
  const py::array a = checkedArray<PoseError>(value, what);
  if (!isReal(a)) {
    throw PoseError(what + ": dtype " + dtypeText(a) + "; a pose needs real numbers");
  }
  const bool single = a.ndim() == 2;
  const bool many = batch && a.ndim() == 3;
  const py::ssize_t rows = a.ndim() >= 2 ? a.shape(a.ndim() - 2) : 0;
  if (!(single || many) || (rows != 3 && rows != 4) || a.shape(a.ndim() - 1) != 4) {
    throw PoseError(what + ": shape " + shapeText(a) + ", expected " +
                    (batch ? "(4, 4), (3, 4), (K, 4, 4) or (K, 3, 4)" : "(4, 4) or (3, 4)"));
  }
  return Doubles::ensure(a);
}

// Indices read as 64 bits of their own signedness, so that a negative or too large one is
// named as it is, not wrapped.
template <class Index>
std::vector<Triangle> trianglesFrom(const py::array& t, std::size_t vertices,
                                    const std::string& name) {
  using Indices = py::array_t<Index, py::array::c_style | py::array::forcecast>;
  const Indices td = Indices::ensure(t);
  std::vector<Triangle> faces(static_cast<std::size_t>(t.shape(0)));
  for (std::size_t i = 0; i < faces.size(); ++i) {
    for (int c = 0; c < 3; ++c) {
      const Index index = td.data()[3 * i + c];
      if (index < 0 || static_cast<unsigned long long>(index) >= vertices) {
        throw MeshError(name + ": triangle " + std::to_string(i) + " references vertex " +
                        std::to_string(index) + ", but the mesh has " +
                        std::to_string(vertices) + " vertices");
      }
      faces[i][c] = static_cast<std::uint32_t>(index);
    }
  }
  return faces;
}

}  // namespace

Pose poseFrom(const py::handle& value, const std::string& what) {
  const Doubles a = poseDoubles(value, what, false);
  return poseAt(a.data(), a.shape(0), what);
}

std::optional<std::size_t> batchSize(const py::handle& value, const std::string& what) {
  const Doubles a = poseDoubles(value, what, true);
  if (a.ndim() == 2) return std::nullopt;
  return static_cast<std::size_t>(a.shape(0));
}

std::vector<Pose> posesFrom(const py::handle& value, const std::string& what,
                            std::size_t count) {
  const Doubles a = poseDoubles(value, what, true);
  if (a.ndim() == 2) return std::vector<Pose>(count, poseAt(a.data(), a.shape(0), what));
  const py::ssize_t rows = a.shape(1);
  std::vector<Pose> poses(static_cast<std::size_t>(a.shape(0)));
  for (std::size_t k = 0; k < poses.size(); ++k) {
    poses[k] = poseAt(a.data() + k * rows * 4, rows, what, static_cast<std::ptrdiff_t>(k));
  }
  return poses;
}

TriangleMesh meshFrom(const py::handle& vertices, const py::handle& triangles,
                      const std::string& name) {
  const py::array v = checkedArray<MeshError>(vertices, name + ": vertices");
  if (!isReal(v)) {
    throw MeshError(name + ": vertices: dtype " + dtypeText(v) + ", expected real numbers");
  }
  if (v.ndim() != 2 || v.shape(1) != 3) {
    throw MeshError(name + ": vertices: shape " + shapeText(v) + ", expected (N, 3)");
  }
  const py::array t = checkedArray<MeshError>(triangles, name + ": triangles");
  if (!isInteger(t)) {
    throw MeshError(name + ": triangles: dtype " + dtypeText(t) +
                    ", expected integers (vertex indices)");
  }
  if (t.ndim() != 2 || t.shape(1) != 3) {
    throw MeshError(name + ": triangles: shape " + shapeText(t) + ", expected (M, 3)");
  }
  const Doubles vd = Doubles::ensure(v);
  std::vector<Vec3> points(static_cast<std::size_t>(v.shape(0)));
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i] = Vec3(vd.data()[3 * i], vd.data()[3 * i + 1], vd.data()[3 * i + 2]);
  }
  std::vector<Triangle> faces = t.dtype().kind() == 'u'
                                    ? trianglesFrom<unsigned long long>(t, points.size(), name)
                                    : trianglesFrom<long long>(t, points.size(), name);
  return TriangleMesh(std::move(points), std::move(faces), name);
}

std::vector<Pose> posesFromQuaternions(const py::handle& quaternions,
                                       const py::handle& translations) {
  const py::array q = checkedArray<PoseError>(quaternions, "quaternions");
  const py::array t = checkedArray<PoseError>(translations, "translations");
  if (!isReal(q) || !isReal(t)) {
    throw PoseError("quaternions, translations: dtypes " + dtypeText(q) + ", " + dtypeText(t) +
                    "; poses need real numbers");
  }
  if (q.ndim() != 2 || q.shape(1) != 4 || t.ndim() != 2 || t.shape(1) != 3 ||
      q.shape(0) != t.shape(0)) {
    throw PoseError("quaternions, translations: shapes " + shapeText(q) + ", " + shapeText(t) +
                    "; expected (K, 4) and (K, 3)");
  }
  const Doubles qd = Doubles::ensure(q), td = Doubles::ensure(t);
  std::vector<Pose> poses(static_cast<std::size_t>(q.shape(0)));
  for (std::size_t k = 0; k < poses.size(); ++k) {
    const double* w = qd.data() + 4 * k;
    const Eigen::Quaterniond rotation(w[0], w[1], w[2], w[3]);
    if (!rotation.coeffs().allFinite() || !(rotation.norm() > 0.0)) {
      throw PoseError("quaternions[" + std::to_string(k) + "]: not a rotation (zero or " +
                      "non-finite)");
    }
    const double* x = td.data() + 3 * k;
    poses[k] = Pose::fromQuaternion(rotation, Vec3(x[0], x[1], x[2]));
    const PoseDefect defect = poseDefect(poses[k]);
    if (defect != PoseDefect::None) {
      throw PoseError("translations[" + std::to_string(k) + "]: " + describe(defect));
    }
  }
  return poses;
}

std::vector<double> realsFrom(const py::handle& values, const std::string& what) {
  const py::array a = checkedArray<SettingsError>(values, what);
  if (!isReal(a) || a.ndim() != 1) {
    throw SettingsError(what + ": shape " + shapeText(a) + ", dtype " + dtypeText(a) +
                        "; expected a 1-d array of real numbers");
  }
  const Doubles d = Doubles::ensure(a);
  return std::vector<double>(d.data(), d.data() + d.size());
}

namespace {

// The 4x4 matrix of `pose`, row-major, at p[0..15].
void writePose(const Pose& pose, double* p) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) p[4 * r + c] = pose.rotation(r, c);
    p[4 * r + 3] = pose.translation[r];
  }
  p[12] = p[13] = p[14] = 0.0;
  p[15] = 1.0;
}

}  // namespace

py::array_t<double> poseArray(const Pose& pose) {
  py::array_t<double> out = newArray<double>({4, 4});
  writePose(pose, out.mutable_data());
  return out;
}

py::array_t<double> poseArrays(const std::vector<Pose>& poses) {
  py::array_t<double> out = newArray<double>({static_cast<py::ssize_t>(poses.size()), 4, 4});
  for (std::size_t k = 0; k < poses.size(); ++k) writePose(poses[k], out.mutable_data() + 16 * k);
  return out;
}

}  // namespace adb::python
