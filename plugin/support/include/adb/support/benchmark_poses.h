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

/// The unit of benchmark distances between two different meshes: the mean of their units,
/// 0.5 * (benchmarkUnit(a) + benchmarkUnit(b)); benchmarkUnit(a) when both boxes are a's.
double benchmarkUnit(const Aabb& boundsA, const Aabb& boundsB);

/// Two copies of a mesh with bounding box `meshBounds`, each randomly rotated about its
/// bounding-box centre, the centres `distance` benchmark units apart along the world x axis.
PosePair benchmarkPoses(const Aabb& meshBounds, double distance, std::mt19937_64& rng);

/// The same for two different meshes (bounding boxes `boundsA` of the first, `boundsB` of the
/// second): each randomly rotated about its own bounding-box centre, the centres `distance`
/// pair units (benchmarkUnit(boundsA, boundsB)) apart along the world x axis. With
/// boundsB == boundsA, the same poses (and draws from `rng`) as the one-mesh overload.
PosePair benchmarkPoses(const Aabb& boundsA, const Aabb& boundsB, double distance,
                        std::mt19937_64& rng);

/// The "robot in a room" poses of FCL's test suite: the first mesh (the environment) fixed at
/// the identity, the second at a uniformly random rotation about its bounding-box centre,
/// with that centre uniformly random in the first mesh's bounding box `boundsA`.
PosePair insidePoses(const Aabb& boundsA, const Aabb& boundsB, std::mt19937_64& rng);

}  // namespace adb
