// Whether the two copies' root bounding boxes overlap in the world: the paper's filter for
// the error rate (only queries whose root boxes overlap count). Decided here, independently
// of every method, as an exact oriented-box test of the mesh's bounding box at each pose.
#pragma once

#include "adb/core/geometry.h"

namespace adb::tradeoff {

/// True when box `box` (mesh coordinates) posed at `a` and at `b` overlaps (touching counts).
bool rootBoxesOverlap(const Aabb& box, const Pose& a, const Pose& b);

}  // namespace adb::tradeoff
