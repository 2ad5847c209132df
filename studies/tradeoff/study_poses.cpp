// Seeded benchmark poses, canonicalised through their quaternions.
#include "study_poses.h"

#include <random>

#include "adb/support/benchmark_poses.h"

namespace adb::tradeoff {
namespace {

std::uint32_t low(std::uint64_t v) { return static_cast<std::uint32_t>(v & 0xFFFFFFFFu); }
std::uint32_t high(std::uint64_t v) { return static_cast<std::uint32_t>(v >> 32); }

QuaternionPose canonical(const Pose& p) {
  return fromQuaternion(Eigen::Quaterniond(p.rotation).normalized(), p.translation);
}

}  // namespace

QuaternionPose fromQuaternion(const Eigen::Quaterniond& q, const Vec3& t) {
  QuaternionPose out;
  out.q = q;
  out.t = t;
  out.pose = Pose::fromQuaternion(q, t);
  return out;
}

std::vector<StudyPose> studyPoses(const Aabb& bounds, double distance, int rotations,
                                  std::uint64_t seed, std::size_t modelIndex,
                                  std::size_t distanceIndex) {
  std::seed_seq sequence{low(seed), high(seed), low(modelIndex), high(modelIndex),
                         low(distanceIndex), high(distanceIndex)};
  std::mt19937_64 rng(sequence);
  std::vector<StudyPose> poses;
  poses.reserve(static_cast<std::size_t>(rotations));
  for (int r = 0; r < rotations; ++r) {
    const PosePair p = benchmarkPoses(bounds, distance, rng);
    poses.push_back(StudyPose{canonical(p.a), canonical(p.b)});
  }
  return poses;
}

}  // namespace adb::tradeoff
