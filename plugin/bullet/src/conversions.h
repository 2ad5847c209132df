// Internal: conversions between Bullet's types and the core's, shared by the algorithms.
#pragma once

#include <LinearMath/btTransform.h>

#include "adb/core/geometry.h"
#include "adb/core/tree.h"

namespace adb::detail {

inline btVector3 toBt(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
                   static_cast<btScalar>(v.z()));
}

inline Vec3 fromBt(const btVector3& v) { return Vec3(v.x(), v.y(), v.z()); }

inline Pose toPose(const btTransform& t) {
  Pose p;
  const btMatrix3x3& b = t.getBasis();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) p.rotation(r, c) = b[r][c];
  }
  p.translation = fromBt(t.getOrigin());
  return p;
}

/// A tree-order triangle of a posed tree, in world coordinates.
inline void worldTriangle(const AdbTree& tree, const Pose& pose, std::uint32_t t, Vec3 out[3]) {
  for (int k = 0; k < 3; ++k) {
    out[k] = pose.rotation * (tree.localVertices()[tree.triangles()[t][k]] + tree.origin()) +
             pose.translation;
  }
}

}  // namespace adb::detail
