// MeshShape: a Bullet collision shape for a concave triangle mesh, backed by an ADB-tree that
// many shapes (bodies) may share.
//
// Its shape type is CUSTOM_CONCAVE_SHAPE_TYPE, which equals SDF_SHAPE_PROXYTYPE in Bullet
// 3.24: Bullet's own convex-concave algorithm would cast it to btSdfCollisionShape, so a world
// using MeshShape must register adb's algorithms for every pair type it can meet (the
// registration call does). The shape's frame is the mesh's own coordinate frame.
#pragma once

#include <BulletCollision/CollisionShapes/btConcaveShape.h>

#include <memory>

#include "adb/bullet/precision.h"
#include "adb/core/mass_properties.h"
#include "adb/core/mesh.h"
#include "adb/core/tree.h"

namespace adb {

/// The data many MeshShapes share: the mesh, its tree and its mass properties. Immutable.
struct MeshData {
  TriangleMesh mesh;
  AdbTree tree;
  MassProperties mass;
  /// Which way the triangles face: +1 closed and wound outward, -1 closed and wound inward,
  /// 0 open (its triangles are two-sided to contact generation).
  int facing = 0;

  /// Builds the tree and the mass properties (throws MeshError/SettingsError at the door).
  static std::shared_ptr<const MeshData> build(TriangleMesh mesh,
                                               const BuildSettings& settings = {});
};

class MeshShape : public btConcaveShape {
 public:
  BT_DECLARE_ALIGNED_ALLOCATOR();

  explicit MeshShape(std::shared_ptr<const MeshData> data);

  /// The tree queries run on (the shared one, or a scaled copy after setLocalScaling).
  const AdbTree& tree() const { return m_scaled ? m_scaled->tree : m_data->tree; }
  const MeshData& data() const { return m_scaled ? *m_scaled : *m_data; }

  // --- btCollisionShape ------------------------------------------------------------------
  void getAabb(const btTransform& t, btVector3& aabbMin, btVector3& aabbMax) const override;
  /// Scales the mesh per axis (positive, finite; throws SettingsError otherwise). A scale
  /// other than (1, 1, 1) builds this shape's own scaled tree once: the shared one stays.
  void setLocalScaling(const btVector3& scaling) override;
  const btVector3& getLocalScaling() const override { return m_scaling; }
  /// The diagonal of the inertia tensor of a body of this mass about its centre of mass, in
  /// the shape's axes. Bullet's rigid bodies assume the shape's frame is the principal frame
  /// (centre of mass at the origin, diagonal tensor); where it is not, put the shape in a
  /// btCompoundShape at principalTransform().inverse(). Closed meshes integrate their
  /// volume; open ones are treated as thin shells.
  void calculateLocalInertia(btScalar mass, btVector3& inertia) const override;
  const char* getName() const override { return "AdbMesh"; }

  // --- btConcaveShape --------------------------------------------------------------------
  /// Calls back every triangle in a leaf whose box overlaps the given box (shape frame).
  void processAllTriangles(btTriangleCallback* callback, const btVector3& aabbMin,
                           const btVector3& aabbMax) const override;

  /// Centre of mass and principal axes in the shape's frame. A body whose shape frame is not
  /// its principal frame puts the shape in a btCompoundShape with the inverse of this.
  btTransform principalTransform() const;

 private:
  std::shared_ptr<const MeshData> m_data;
  std::shared_ptr<const MeshData> m_scaled;  // set when the scaling is not (1, 1, 1)
  btVector3 m_scaling{1, 1, 1};
};

}  // namespace adb
