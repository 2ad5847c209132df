// Oriented-box overlap by the separating-axis theorem (15 axes: 3 + 3 face normals, 9 edge
// cross products), in the frame of box A.
#include "root_overlap.h"

#include <cmath>

namespace adb::tradeoff {

bool rootBoxesOverlap(const Aabb& boxA, const Pose& a, const Aabb& boxB, const Pose& b) {
  const Vec3 ha = 0.5 * boxA.extent();
  const Vec3 hb = 0.5 * boxB.extent();
  // B's orientation and centre in A's frame.
  const Mat3 r = a.rotation.transpose() * b.rotation;
  const Vec3 worldA = a.apply(boxA.center());
  const Vec3 worldB = b.apply(boxB.center());
  const Vec3 t = a.rotation.transpose() * (worldB - worldA);
  // The epsilon keeps near-parallel edge pairs (cross product ~0) from separating wrongly.
  const Mat3 absR = r.cwiseAbs().array() + 1e-12;
  for (int i = 0; i < 3; ++i) {  // A's face normals
    if (std::abs(t[i]) > ha[i] + hb.dot(absR.row(i))) return false;
  }
  for (int j = 0; j < 3; ++j) {  // B's face normals
    if (std::abs(t.dot(r.col(j))) > ha.dot(absR.col(j)) + hb[j]) return false;
  }
  for (int i = 0; i < 3; ++i) {  // edge x edge
    const int i1 = (i + 1) % 3, i2 = (i + 2) % 3;
    for (int j = 0; j < 3; ++j) {
      const int j1 = (j + 1) % 3, j2 = (j + 2) % 3;
      const double ra = ha[i1] * absR(i2, j) + ha[i2] * absR(i1, j);
      const double rb = hb[j1] * absR(i, j2) + hb[j2] * absR(i, j1);
      if (std::abs(t[i2] * r(i1, j) - t[i1] * r(i2, j)) > ra + rb) return false;
    }
  }
  return true;
}

bool rootBoxesOverlap(const Aabb& box, const Pose& a, const Pose& b) {
  return rootBoxesOverlap(box, a, box, b);
}

}  // namespace adb::tradeoff
