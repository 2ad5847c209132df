// Random poses of the benchmark procedure.
#include "adb/support/benchmark_poses.h"

#include <cmath>

namespace adb {

double benchmarkUnit(const Aabb& meshBounds) {
  const double half = 0.5 * meshBounds.extent().maxCoeff();
  return half > 0.0 && std::isfinite(half) ? half : 1.0;
}

Eigen::Quaterniond randomRotation(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  const double u1 = uni(rng), u2 = uni(rng), u3 = uni(rng);
  const double twoPi = 2.0 * M_PI;
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  return Eigen::Quaterniond(b * std::cos(twoPi * u3), a * std::sin(twoPi * u2),
                            a * std::cos(twoPi * u2), b * std::sin(twoPi * u3));
}

double benchmarkUnit(const Aabb& boundsA, const Aabb& boundsB) {
  // u + u is exact and so is halving it: one box gives exactly benchmarkUnit(box).
  return 0.5 * (benchmarkUnit(boundsA) + benchmarkUnit(boundsB));
}

PosePair benchmarkPoses(const Aabb& meshBounds, double distance, std::mt19937_64& rng) {
  return benchmarkPoses(meshBounds, meshBounds, distance, rng);
}

PosePair benchmarkPoses(const Aabb& boundsA, const Aabb& boundsB, double distance,
                        std::mt19937_64& rng) {
  const Vec3 ca = boundsA.center(), cb = boundsB.center();
  const double unit = benchmarkUnit(boundsA, boundsB);
  PosePair p;
  const Mat3 ra = randomRotation(rng).toRotationMatrix();
  const Mat3 rb = randomRotation(rng).toRotationMatrix();
  // Rotate about the bounding-box centre, then place the centres on the x axis.
  p.a = Pose{ra, -(ra * ca)};
  p.b = Pose{rb, -(rb * cb) + Vec3(distance * unit, 0.0, 0.0)};
  return p;
}

PosePair insidePoses(const Aabb& boundsA, const Aabb& boundsB, std::mt19937_64& rng) {
  const Mat3 rb = randomRotation(rng).toRotationMatrix();
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  Vec3 centre;
  for (int k = 0; k < 3; ++k) {
    centre[k] = boundsA.lo[k] + uni(rng) * (boundsA.hi[k] - boundsA.lo[k]);
  }
  PosePair p;  // a: the identity
  p.b = Pose{rb, centre - rb * boundsB.center()};
  return p;
}

}  // namespace adb
