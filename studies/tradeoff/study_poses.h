// The poses of the study: Zachmann's benchmark poses (adb::benchmarkPoses) per case and
// distance, from a generator seeded by (--seed, case index, distance index), or the "robot in
// a room" poses (adb::insidePoses) per case, seeded by (--seed, case index, a tag no distance
// index takes), so that they do not depend on which methods run; written as quaternion +
// translation. A case's index is its position on the command line (a model, or a model and
// what it is tested against), so a run without pairs has today's poses.
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

/// One body's pose: world = R(q) * x + t, x in its mesh's file coordinates.
struct QuaternionPose {
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  Vec3 t = Vec3::Zero();
  Pose pose;  ///< Pose::fromQuaternion(q, t): what the methods are queried with
};

struct StudyPose {
  QuaternionPose a, b;
};

/// `rotations` pose pairs at `distance` benchmark units (adb::benchmarkUnit(boundsA, boundsB))
/// for meshes with bounding boxes `boundsA` and `boundsB` (the same box for two copies).
std::vector<StudyPose> studyPoses(const Aabb& boundsA, const Aabb& boundsB, double distance,
                                  int rotations, std::uint64_t seed, std::size_t caseIndex,
                                  std::size_t distanceIndex);

/// `count` poses with A at the identity and B's box centre uniformly random in A's box.
std::vector<StudyPose> insideStudyPoses(const Aabb& boundsA, const Aabb& boundsB, int count,
                                        std::uint64_t seed, std::size_t caseIndex);

/// The distance of the two bodies' box centres at `pose`, in benchmark units, rounded to the
/// nearest 0.1: the distance column of --poses inside, which sets no distance.
double measuredDistance(const StudyPose& pose, const Aabb& boundsA, const Aabb& boundsB);

/// The pose of a (q, t) as read back from queries.csv: the same conversion the tool uses.
QuaternionPose fromQuaternion(const Eigen::Quaterniond& q, const Vec3& t);

}  // namespace adb::tradeoff
