// nearFaceCorners: the root box's eight corners in the world, the four farthest along a
// direction.
#include "near_face_corners.h"

#include <algorithm>

#include "adb/bullet/mesh_shape.h"
#include "conversions.h"

namespace adb::detail {

std::array<btVector3, 4> nearFaceCorners(const MeshShape& mesh, const btTransform& pose,
                                         const btVector3& direction) {
  const AdbTree& tree = mesh.tree();
  const Node& root = tree.root();
  btVector3 corners[8];
  btScalar along[8];
  for (int k = 0; k < 8; ++k) {
    const Vec3 local(k & 1 ? root.boxHi().x() : root.boxLo().x(),
                     k & 2 ? root.boxHi().y() : root.boxLo().y(),
                     k & 4 ? root.boxHi().z() : root.boxLo().z());
    corners[k] = pose(toBt(local + tree.origin()));
    along[k] = corners[k].dot(direction);
  }
  int order[8] = {0, 1, 2, 3, 4, 5, 6, 7};
  std::sort(order, order + 8, [&](int x, int y) { return along[x] > along[y]; });
  return {corners[order[0]], corners[order[1]], corners[order[2]], corners[order[3]]};
}

}  // namespace adb::detail
