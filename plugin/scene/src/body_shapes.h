// Internal: the collision shapes of a scene's bodies for one backend, and what pictures and
// measures need of them. Meshes are read or generated once per named shape and shared by the
// bodies that use it: one tree per shape and frame, one MeshShape per body (as adb's
// algorithms expect), one GImpact shape per shape.
#pragma once

#include <btBulletCollisionCommon.h>

#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "adb/bullet/mesh_shape.h"
#include "adb/bullet/triangle_arrays.h"
#include "adb/scene/scene.h"
#include "adb/scene/scene_world.h"

namespace adb::scene::detail {

/// A body's shape as the world gets it.
struct BodyShape {
  btCollisionShape* shape = nullptr;
  /// The mesh behind it (nullptr for primitives): its tree, vertices and mass properties.
  std::shared_ptr<const MeshData> mesh;
  /// The scene's pose of the body is that of the mesh's own frame (unless it places the
  /// centre of mass: identity); Bullet's body is placed at pose * meshFromShape (the
  /// principal frame of a dynamic mesh body).
  Pose meshFromShape;
  const TriangleMesh* display = nullptr;  ///< in the shape's frame
};

class BodyShapes {
 public:
  /// `convex` makes the moving meshes' shapes under Backend::Convex.
  BodyShapes(const Scene& scene, Backend backend, ConvexShapeMaker convex);

  /// The shape for body `index` of the scene (call once per body).
  BodyShape make(const BodySpec& body);

  /// Triangles over the mesh shapes made so far, one count per body.
  std::size_t triangles() const { return m_triangles; }

 private:
  const TriangleMesh& sourceMesh(std::size_t shape);
  std::shared_ptr<const MeshData> meshData(std::size_t shape, ShapeFrame frame);
  btCollisionShape* meshShape(std::size_t shape, const std::shared_ptr<const MeshData>& data,
                              BodySpec::Kind kind);
  BodyShape primitive(std::size_t shape);
  btCollisionShape* keep(std::unique_ptr<btCollisionShape> shape);

  const Scene& m_scene;
  Backend m_backend;
  ConvexShapeMaker m_convex;
  std::map<std::size_t, TriangleMesh> m_sources;  // per shape: read or generated, scaled
  std::map<std::pair<std::size_t, ShapeFrame>, std::shared_ptr<const MeshData>> m_data;
  std::map<std::pair<std::size_t, ShapeFrame>, btCollisionShape*> m_shared;  // GImpact/BVH
  std::map<std::size_t, TriangleMesh> m_displays;  // per primitive shape
  std::vector<std::unique_ptr<TriangleArrays>> m_arrays;
  std::vector<std::unique_ptr<btCollisionShape>> m_shapes;
  std::size_t m_triangles = 0;
};

}  // namespace adb::scene::detail
