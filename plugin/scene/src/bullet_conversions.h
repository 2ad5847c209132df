// Internal: the scene layer's conversions between Bullet's types and the core's.
#pragma once

#include <LinearMath/btTransform.h>

#include "adb/core/geometry.h"

namespace adb::scene::detail {

inline btVector3 toBt(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
                   static_cast<btScalar>(v.z()));
}

inline btTransform toBt(const Pose& p) {
  btMatrix3x3 basis;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) basis[r][c] = static_cast<btScalar>(p.rotation(r, c));
  }
  return btTransform(basis, toBt(p.translation));
}

inline Pose poseOf(const btTransform& t) {
  Pose p;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) p.rotation(r, c) = t.getBasis()[r][c];
    p.translation[r] = t.getOrigin()[r];
  }
  return p;
}

}  // namespace adb::scene::detail
