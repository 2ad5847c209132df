// TriangleArrays: a TriangleMesh as Bullet's striding mesh interface, for Bullet's own mesh shapes
// (btBvhTriangleMeshShape, btGImpactMeshShape) beside adb's: they read the mesh through a
// btTriangleIndexVertexArray that must outlive them, and this owns the arrays it points into.
#pragma once

#include <btBulletCollisionCommon.h>

#include <memory>
#include <vector>

#include "adb/core/mesh.h"

namespace adb {

struct TriangleArrays {
  std::vector<btScalar> vertices;
  std::vector<int> indices;
  std::unique_ptr<btTriangleIndexVertexArray> array;

  explicit TriangleArrays(const TriangleMesh& mesh) {
    for (const Vec3& v : mesh.vertices()) {
      for (int k = 0; k < 3; ++k) vertices.push_back(static_cast<btScalar>(v[k]));
    }
    for (const Triangle& t : mesh.triangles()) {
      for (std::uint32_t i : t) indices.push_back(static_cast<int>(i));
    }
    array = std::make_unique<btTriangleIndexVertexArray>(
        static_cast<int>(mesh.triangleCount()), indices.data(), 3 * static_cast<int>(sizeof(int)),
        static_cast<int>(mesh.vertices().size()), vertices.data(),
        3 * static_cast<int>(sizeof(btScalar)));
  }
};

}  // namespace adb
