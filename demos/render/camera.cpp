#include "render/camera.h"

#include <algorithm>
#include <cmath>

namespace adb::render {

Camera cameraFraming(const Vec3& boundsMin, const Vec3& boundsMax, const Vec3& viewDirection,
                     double fovYDegrees) {
  Camera c;
  c.fovYDegrees = std::clamp(fovYDegrees, 1.0, 170.0);
  const Vec3 centre = 0.5 * (boundsMin + boundsMax);
  // The box's bounding sphere fits the narrower field of view (taken as the vertical one,
  // pictures being wider than tall), with a tenth to spare.
  const double radius = std::max(0.5 * (boundsMax - boundsMin).norm(), 1e-6);
  const double halfAngle = 0.5 * c.fovYDegrees * M_PI / 180.0;
  const double distance = 1.1 * radius / std::sin(halfAngle);
  const Vec3 direction =
      viewDirection.norm() > 0 ? Vec3(viewDirection.normalized()) : Vec3(-Vec3::UnitZ());
  c.target = centre;
  c.eye = centre - distance * direction;
  // Looking straight up or down: y cannot be the up direction.
  c.up = std::abs(direction.dot(Vec3::UnitY())) > 0.99 ? Vec3::UnitZ() : Vec3::UnitY();
  return c;
}

}  // namespace adb::render
