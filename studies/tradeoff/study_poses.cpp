// Seeded benchmark and inside poses, canonicalised through their quaternions.
#include "study_poses.h"

#include <cmath>
#include <random>

#include "adb/support/benchmark_poses.h"

namespace adb::tradeoff {
namespace {

// The inside poses' stream: in place of a distance index, which never reaches it.
constexpr std::uint64_t kInsideTag = ~std::uint64_t{0};

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

std::vector<StudyPose> studyPoses(const Aabb& boundsA, const Aabb& boundsB, double distance,
                                  int rotations, std::uint64_t seed, std::size_t caseIndex,
                                  std::size_t distanceIndex) {
  std::seed_seq sequence{low(seed), high(seed), low(caseIndex), high(caseIndex),
                         low(distanceIndex), high(distanceIndex)};
  std::mt19937_64 rng(sequence);
  std::vector<StudyPose> poses;
  poses.reserve(static_cast<std::size_t>(rotations));
  for (int r = 0; r < rotations; ++r) {
    const PosePair p = benchmarkPoses(boundsA, boundsB, distance, rng);
    poses.push_back(StudyPose{canonical(p.a), canonical(p.b)});
  }
  return poses;
}

std::vector<StudyPose> insideStudyPoses(const Aabb& boundsA, const Aabb& boundsB, int count,
                                        std::uint64_t seed, std::size_t caseIndex) {
  std::seed_seq sequence{low(seed),      high(seed),      low(caseIndex),
                         high(caseIndex), low(kInsideTag), high(kInsideTag)};
  std::mt19937_64 rng(sequence);
  std::vector<StudyPose> poses;
  poses.reserve(static_cast<std::size_t>(count));
  for (int r = 0; r < count; ++r) {
    const PosePair p = insidePoses(boundsA, boundsB, rng);
    poses.push_back(StudyPose{canonical(p.a), canonical(p.b)});
  }
  return poses;
}

double measuredDistance(const StudyPose& pose, const Aabb& boundsA, const Aabb& boundsB) {
  const Vec3 a = pose.a.pose.apply(boundsA.center());
  const Vec3 b = pose.b.pose.apply(boundsB.center());
  // k / 10.0 is the double nearest to k tenths: it prints and groups as typed.
  return std::round(10.0 * (b - a).norm() / benchmarkUnit(boundsA, boundsB)) / 10.0;
}

}  // namespace adb::tradeoff
