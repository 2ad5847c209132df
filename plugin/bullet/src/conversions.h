// Internal: what the algorithms share beyond the public conversions (adb/bullet/conversions.h).
#pragma once

#include "adb/bullet/conversions.h"
#include "adb/core/tree.h"

namespace adb::detail {

/// A tree-order triangle of a posed tree, in world coordinates.
inline void worldTriangle(const AdbTree& tree, const Pose& pose, std::uint32_t t, Vec3 out[3]) {
  for (int k = 0; k < 3; ++k) {
    out[k] = pose.apply(tree.localVertices()[tree.triangles()[t][k]] + tree.origin());
  }
}

}  // namespace adb::detail
