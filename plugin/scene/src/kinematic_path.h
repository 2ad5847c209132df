// Internal: where a body that follows a motion is at a given time.
#pragma once

#include <vector>

#include "adb/core/geometry.h"
#include "adb/scene/scene.h"

namespace adb::scene::detail {

/// A constant twist from `start`: translation at `linear`, rotation at `angular` (world
/// frame, about the body's origin).
Pose twistPose(const Pose& start, const Vec3& linear, const Vec3& angular, double time);

/// Keyframes interpolated (positions linearly, rotations by slerp), held after the last; the
/// body's initial pose `start` counts as a keyframe at time 0 when the first comes later.
Pose keyframePose(const Pose& start, const std::vector<Keyframe>& keys, double time);

/// The pose of a body following `motion` at `time`.
Pose motionPose(const Pose& start, const MotionSpec& motion, double time);

}  // namespace adb::scene::detail
