// Conversions between Bullet's types and the core's: one place for every layer and program.
// Bullet's btScalar may be float or double (adb/bullet/precision.h); the core is double.
#pragma once

#include <LinearMath/btTransform.h>

#include <algorithm>
#include <limits>

#include "adb/core/geometry.h"

namespace adb {

inline btVector3 toBt(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
                   static_cast<btScalar>(v.z()));
}

inline Vec3 fromBt(const btVector3& v) { return Vec3(v.x(), v.y(), v.z()); }

/// A core pose as a btTransform: the rotation entry by entry (no quaternion in between).
inline btTransform toBt(const Pose& p) {
  btMatrix3x3 basis;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) basis[r][c] = static_cast<btScalar>(p.rotation(r, c));
  }
  return btTransform(basis, toBt(p.translation));
}

/// The core's tolerance for a rotation: max |R^T R - I| <= 1e-6 (adb/core/query.h, poseDefect).
constexpr double kCoreOrthonormal = 1e-6;
/// How far from orthonormal a btScalar basis may be and still be rounding: in float, a basis
/// from a quaternion is off by up to 0.95e-6, a compound child's (the product of two) by up
/// to 1.3e-6 and a grandchild's 1.7e-6 (1e6 random rotations each), past the core's 1e-6.
/// 128 float epsilons (1.5e-5) leave a margin for deeper products; a basis scaled, sheared or
/// drifted further than that is a defect. In double the core's own 1e-6 is the larger.
constexpr double kBasisRounding = std::max(
    kCoreOrthonormal, 128.0 * static_cast<double>(std::numeric_limits<btScalar>::epsilon()));

/// A btTransform as a core pose. A basis the core would refuse but within kBasisRounding of
/// orthonormal is made orthonormal (one Newton step towards its polar factor, the nearest
/// rotation: the error e becomes about e^2, 2e-10 at most), so that a pose rounded in float is
/// not refused. Any other basis is passed on exactly as it is: one the core accepts keeps its
/// bits (a simulation runs as it did before), a defective one is left for poseDefect to name.
inline Pose toPose(const btTransform& t) {
  Pose p;
  const btMatrix3x3& b = t.getBasis();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) p.rotation(r, c) = b[r][c];
  }
  p.translation = fromBt(t.getOrigin());
  const Mat3 gram = p.rotation.transpose() * p.rotation;
  const double off = (gram - Mat3::Identity()).cwiseAbs().maxCoeff();
  // Written so that a NaN (off is then NaN) is passed on unchanged.
  if (off > kCoreOrthonormal && off <= kBasisRounding) {
    p.rotation = p.rotation * (1.5 * Mat3::Identity() - 0.5 * gram);
  }
  return p;
}

}  // namespace adb
