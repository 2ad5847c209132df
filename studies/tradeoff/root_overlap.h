// Whether the two bodies' root bounding boxes overlap in the world: the paper's filter for
// the error rate (only queries whose root boxes overlap count). Decided here, independently
// of every method, as an exact oriented-box test of each mesh's bounding box at its pose.
#pragma once

#include "adb/core/geometry.h"

namespace adb::tradeoff {

/// True when box `boxA` (mesh A's coordinates) posed at `a` and box `boxB` (mesh B's) posed
/// at `b` overlap (touching counts).
bool rootBoxesOverlap(const Aabb& boxA, const Pose& a, const Aabb& boxB, const Pose& b);

/// Two copies of one mesh: rootBoxesOverlap(box, a, box, b).
bool rootBoxesOverlap(const Aabb& box, const Pose& a, const Pose& b);

}  // namespace adb::tradeoff
