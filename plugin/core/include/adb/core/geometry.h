// Small geometric value types shared by the core: vectors, axis-aligned boxes and rigid poses.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace adb {

using Vec3 = Eigen::Vector3d;
using Vec3f = Eigen::Vector3f;
using Mat3 = Eigen::Matrix3d;

/// Axis-aligned box [lo, hi]. Empty when lo > hi on any axis (the default).
struct Aabb {
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = Vec3::Constant(-std::numeric_limits<double>::infinity());

  void grow(const Vec3& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  void grow(const Aabb& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  bool empty() const { return (lo.array() > hi.array()).any(); }
  Vec3 center() const { return 0.5 * (lo + hi); }
  Vec3 extent() const { return hi - lo; }
};

/// An oriented box: centre, axes (the columns of a rotation) and half extents along them.
struct OrientedBox {
  Vec3 centre = Vec3::Zero();
  Mat3 axes = Mat3::Identity();
  Vec3 half = Vec3::Zero();
};

/// A rigid pose: world = rotation * x + translation, with x in the mesh's own (file)
/// coordinates. The rotation must be orthonormal; it is not re-normalised per query.
struct Pose {
  Mat3 rotation = Mat3::Identity();
  Vec3 translation = Vec3::Zero();

  static Pose fromQuaternion(const Eigen::Quaterniond& q, const Vec3& t) {
    return Pose{q.normalized().toRotationMatrix(), t};
  }

  /// The point `x` (in this pose's local coordinates) in world coordinates.
  Vec3 apply(const Vec3& x) const { return rotation * x + translation; }
  /// This pose after `local`: world_from_local = (*this) * local.
  Pose operator*(const Pose& local) const {
    return Pose{rotation * local.rotation, rotation * local.translation + translation};
  }
  /// The inverse transform (the rotation's transpose: it must be orthonormal).
  Pose inverse() const {
    const Mat3 rt = rotation.transpose();
    return Pose{rt, -(rt * translation)};
  }
};

}  // namespace adb
