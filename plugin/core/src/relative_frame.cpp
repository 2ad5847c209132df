#include "relative_frame.h"

#include <algorithm>

namespace adb::detail {
namespace {

// Transform-rounding tolerance of the overlap test, relative to the scene's magnitude.
constexpr double kOverlapRelativeSlack = 1e-12;

void broadcast(const Mat3& m, Lanes out[3][3]) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out[r][c] = Lanes::all(m(r, c));
  }
}

void broadcast(const Vec3& v, Lanes out[3]) {
  for (int k = 0; k < 3; ++k) out[k] = Lanes::all(v[k]);
}

}  // namespace

RelativeFrame RelativeFrame::between(const AdbTree& a, const Pose& poseA, const AdbTree& b,
                                     const Pose& poseB) {
  // World placement of each tree's local frame: world = R x_local + (R origin + t).
  const Vec3 ta = poseA.apply(a.origin());
  const Vec3 tb = poseB.apply(b.origin());
  RelativeFrame f;
  // world -> A is the inverse of A's rotation; exact inverses keep the frame consistent for
  // rotations that are orthonormal only to the pose tolerance.
  const Mat3 worldToA = poseA.rotation.inverse();
  f.rBA = worldToA * poseB.rotation;
  f.tBA = worldToA * (tb - ta);
  f.rAB = f.rBA.inverse();
  f.tAB = -(f.rAB * f.tBA);
  const auto radius = [](const Node& n) {
    return std::max(n.boxLo().cwiseAbs().maxCoeff(), n.boxHi().cwiseAbs().maxCoeff());
  };
  f.slack = kOverlapRelativeSlack * (f.tBA.norm() + radius(a.root()) + radius(b.root()));
  broadcast(f.rBA, f.lanes.rBA);
  broadcast(f.rBA.cwiseAbs(), f.lanes.absBA);
  broadcast(f.tBA, f.lanes.tBA);
  broadcast(f.rAB, f.lanes.rAB);
  broadcast(f.rAB.cwiseAbs(), f.lanes.absAB);
  broadcast(f.tAB, f.lanes.tAB);
  return f;
}

}  // namespace adb::detail
