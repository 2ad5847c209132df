// Poses of Zachmann's benchmark procedure (docs/benchmark.md), shared by the
// tests, the demos and the trade-off study so that all of them query the same configurations.
#pragma once

#include <random>

#include "adb/core/geometry.h"

namespace adb {

struct PosePair {
  Pose a, b;
};

/// The unit of benchmark distances: half the largest edge of the mesh's bounding box (as if
/// the object were scaled to fit [-1, 1]^3). Never 0: a point-sized mesh gets 1.
double benchmarkUnit(const Aabb& meshBounds);

/// A uniformly random rotation (Shoemake's method) from `rng`.
Eigen::Quaterniond randomRotation(std::mt19937_64& rng);

/// Two copies of a mesh with bounding box `meshBounds`, each randomly rotated about its
/// bounding-box centre, the centres `distance` benchmark units apart along the world x axis.
PosePair benchmarkPoses(const Aabb& meshBounds, double distance, std::mt19937_64& rng);

}  // namespace adb
