// The poses of the study: Zachmann's benchmark poses (adb::benchmarkPoses) per model and
// distance, from a generator seeded by (--seed, model index, distance index) so that they do
// not depend on which methods run, and written as quaternion + translation.
//
// Every method is queried with the pose rebuilt from the quaternion that goes into
// queries.csv (Pose::fromQuaternion), so that re-reading the CSV (%.17g round-trips a double)
// gives bit-identical poses and therefore the tool's own answers.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "adb/core/geometry.h"

namespace adb::tradeoff {

/// One copy's pose: world = R(q) * x + t, x in the mesh's file coordinates.
struct QuaternionPose {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  Vec3 t = Vec3::Zero();
  Pose pose;  ///< Pose::fromQuaternion(q, t): what the methods are queried with
};

struct StudyPose {
  QuaternionPose a, b;
};

/// `rotations` pose pairs at `distance` benchmark units for a mesh with bounding box `bounds`.
std::vector<StudyPose> studyPoses(const Aabb& bounds, double distance, int rotations,
                                  std::uint64_t seed, std::size_t modelIndex,
                                  std::size_t distanceIndex);

/// The pose of a (q, t) as read back from queries.csv: the same conversion the tool uses.
QuaternionPose fromQuaternion(const Eigen::Quaterniond& q, const Vec3& t);

}  // namespace adb::tradeoff
