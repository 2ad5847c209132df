// MeshShape: a Bullet collision shape for a concave triangle mesh, backed by an ADB-tree that
// many shapes (bodies) may share.
//
// Its shape type is CUSTOM_CONCAVE_SHAPE_TYPE, which equals SDF_SHAPE_PROXYTYPE in Bullet
// 3.24: Bullet's own convex-concave algorithm would cast it to btSdfCollisionShape, so a world
// using MeshShape must register adb's algorithms for every pair type it can meet (the
// registration call does).
//
// The shape's frame is the mesh's own coordinate frame by default, or on request its principal
// frame (MeshData::build with ShapeFrame::Principal), which is what Bullet's rigid bodies assume:
// centre of mass at the origin, inertia diagonal. MeshData::meshFromShape keeps the way back
// to the original coordinates, for placing a rendered mesh.
#pragma once

#include <BulletCollision/CollisionShapes/btConcaveShape.h>

#include <memory>

#include "adb/bullet/detail/once_flag.h"
#include "adb/bullet/precision.h"
#include "adb/core/mass_properties.h"
#include "adb/core/mesh.h"
#include "adb/core/tree.h"

class btTriangleRaycastCallback;
class btTriangleConvexcastCallback;

namespace adb {

/// The frame a MeshData's vertices are expressed in (the shape's frame).
enum class ShapeFrame {
  Mesh,       ///< the mesh's own coordinates, unchanged
  Principal,  ///< centre of mass at the origin, principal axes along x, y, z (moments ascending)
};

/// The data many MeshShapes share: the mesh, its tree and its mass properties. Immutable.
struct MeshData {
  TriangleMesh mesh;  ///< in the shape's frame
  AdbTree tree;
  MassProperties mass;  ///< in the shape's frame
  /// Which way the triangles face: +1 closed and wound outward, -1 closed and wound inward,
  /// 0 open (its triangles are two-sided to contact generation).
  int facing = 0;
  /// The shape's frame in the original mesh's coordinates: x_mesh = rotation * x_shape +
  /// translation (proper rotation). The identity for ShapeFrame::Mesh. A rendered mesh in its
  /// original coordinates goes at body transform * inverse(meshFromShape); under
  /// setLocalScaling, x_shape is the shape's unscaled coordinates.
  Pose meshFromShape;
  detail::OnceFlag inertiaWarning;  ///< calculateLocalInertia warns once per MeshData

  /// Builds the tree and the mass properties (throws MeshError/SettingsError at the door),
  /// in the mesh's own frame or, with ShapeFrame::Principal, in its principal frame (the
  /// vertices moved there: a body's centre of mass and axes are then the shape's own).
  static std::shared_ptr<const MeshData> build(TriangleMesh mesh,
                                               const BuildSettings& settings = {},
                                               ShapeFrame frame = ShapeFrame::Mesh);
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
  /// Strong guarantee: if that build throws (MeshError: the scaled mesh beyond what a tree
  /// holds), the shape is unchanged.
  void setLocalScaling(const btVector3& scaling) override;
  const btVector3& getLocalScaling() const override { return m_scaling; }
  /// The diagonal of the inertia tensor of a body of this mass about its centre of mass, in
  /// the shape's axes. Bullet's rigid bodies assume the shape's frame is the principal frame
  /// (centre of mass at the origin, diagonal tensor): exact for data built with
  /// ShapeFrame::Principal. Otherwise, if the centre of mass is off the origin or the tensor
  /// off diagonal (beyond 1e-6 relative), warns once per MeshData through adb::warn
  /// (adb/bullet/warnings.h), since the body would turn about the wrong point; a shape
  /// kept in the mesh frame goes in a btCompoundShape at principalTransform().inverse().
  /// Closed meshes integrate their volume; open ones are treated as thin shells.
  void calculateLocalInertia(btScalar mass, btVector3& inertia) const override;
  const char* getName() const override { return "AdbMesh"; }

  // --- serialization (mesh_serialization.cpp) -------------------------------------------
  /// Written as Bullet's btTriangleMeshShapeData, so that btDefaultSerializer keeps the mesh:
  /// Bullet's btBulletWorldImporter reads it back as a btBvhTriangleMeshShape, and
  /// adb::loadMeshShapes (adb/bullet/mesh_serialization.h) as a MeshShape.
  int calculateSerializeBufferSize() const override;
  /// The unscaled mesh (vertices as doubles, 32-bit indices, one part), the local scaling
  /// (as float: Bullet's format) and the margin; no tree (rebuilt on load) and no
  /// meshFromShape. Throws MeshError, through Bullet's serializer, for a mesh beyond the
  /// format's 32-bit chunk sizes (about 67M vertices or 178M triangles).
  const char* serialize(void* dataBuffer, btSerializer* serializer) const override;

  // --- btConcaveShape --------------------------------------------------------------------
  /// Calls back every triangle in a leaf whose box overlaps the given box (shape frame).
  /// Bullet's rayTest and convexSweepTest reach a custom concave shape only through here,
  /// with the box around the whole ray or sweep; a btTriangleRaycastCallback or a
  /// btTriangleConvexcastCallback is recognised and sent to performRaycast or
  /// performConvexcast instead (the box is then ignored: the cast defines the query).
  void processAllTriangles(btTriangleCallback* callback, const btVector3& aabbMin,
                           const btVector3& aabbMax) const override;

  /// The ray callback->m_from -> m_to (shape frame) through the tree, nearest leaf first,
  /// skipping leaves entered beyond callback->m_hitFraction (which each hit lowers). Each
  /// candidate goes to callback->processTriangle with part 0 and the mesh's triangle index
  /// and vertices, as btBvhTriangleMeshShape::performRaycast reports them: same hits.
  void performRaycast(btTriangleRaycastCallback* callback) const;
  /// The convex sweep callback->m_convexShape from m_convexShapeFrom to m_convexShapeTo
  /// (world; the mesh at m_triangleToWorld) through the tree, nearest leaf first. Each
  /// candidate triangle gets the cast btTriangleConvexcastCallback::processTriangle makes
  /// (btContinuousConvexCollision, same margin and allowed penetration), run here so that
  /// its fraction is known: hits below the bound go to callback->reportHit, and the bound
  /// becomes the smallest of m_hitFraction and reportHit's return values (the closest hit
  /// for Bullet's closest-hit callbacks; unchanged for callbacks that collect every hit).
  /// An override of processTriangle in a subclass is therefore not called. A sweep that
  /// rotates is bounded by the convex's angular-motion sphere, so no rotation is refused.
  /// CCD: btDiscreteDynamicsWorld sweeps a convex body's CCD sphere with convexSweepTest,
  /// which comes here, so a fast convex body does not tunnel through a MeshShape. A body
  /// whose own shape is a MeshShape gets no CCD: Bullet sweeps only convex bodies and
  /// ignores the CCD settings of others (give such a body a convex proxy or smaller steps).
  void performConvexcast(btTriangleConvexcastCallback* callback) const;

  /// Centre of mass and principal axes in the shape's frame (the identity, to rounding, for
  /// ShapeFrame::Principal). A body whose shape frame is not its principal frame puts the
  /// shape in a btCompoundShape with the inverse of this.
  btTransform principalTransform() const;

 private:
  std::shared_ptr<const MeshData> m_data;
  std::shared_ptr<const MeshData> m_scaled;  // set when the scaling is not (1, 1, 1)
  btVector3 m_scaling{1, 1, 1};
};

}  // namespace adb
