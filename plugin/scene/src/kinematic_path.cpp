#include "kinematic_path.h"

#include <algorithm>

namespace adb::scene::detail {

Pose twistPose(const Pose& start, const Vec3& linear, const Vec3& angular, double time) {
  const double angle = angular.norm() * time;
  Mat3 turn = Mat3::Identity();
  if (angle != 0.0) turn = Eigen::AngleAxisd(angle, angular.normalized()).toRotationMatrix();
  return Pose{turn * start.rotation, start.translation + linear * time};
}

Pose keyframePose(const Pose& start, const std::vector<Keyframe>& keys, double time) {
  if (keys.empty()) return start;
  Keyframe before{0.0, start};
  for (const Keyframe& key : keys) {
    if (time < key.time) {
      const double span = key.time - before.time;
      // Keyframes are strictly increasing (the loader checks), so span > 0 but for the
      // implicit first one at time 0 when the first keyframe is also at 0.
      const double s = span > 0.0 ? std::clamp((time - before.time) / span, 0.0, 1.0) : 1.0;
      const Eigen::Quaterniond q0(before.pose.rotation), q1(key.pose.rotation);
      return Pose{q0.slerp(s, q1).normalized().toRotationMatrix(),
                  (1.0 - s) * before.pose.translation + s * key.pose.translation};
    }
    before = key;
  }
  return keys.back().pose;
}

Pose motionPose(const Pose& start, const MotionSpec& motion, double time) {
  return motion.twist ? twistPose(start, motion.linear, motion.angular, time)
                      : keyframePose(start, motion.keyframes, time);
}

}  // namespace adb::scene::detail
