// A pinhole camera looking from `eye` at `target`.
#pragma once

#include "adb/core/geometry.h"

namespace adb::render {

struct Camera {
  Vec3 eye = Vec3(0, 0, 5);
  Vec3 target = Vec3::Zero();
  Vec3 up = Vec3::UnitY();
  double fovYDegrees = 40;
};

/// A camera looking along `viewDirection` (from the eye towards the target) at the centre of
/// the box [boundsMin, boundsMax], far enough that the whole box is in view with a margin.
Camera cameraFraming(const Vec3& boundsMin, const Vec3& boundsMax, const Vec3& viewDirection,
                     double fovYDegrees = 40);

}  // namespace adb::render
