// Mass properties of a triangle mesh for rigid-body dynamics: volume, area, centre of mass and
// the unit-mass inertia tensor with its principal frame (what a physics engine's collision
// shape needs for calculateLocalInertia / principal-axis transforms).
//
// Two mass models:
//  - SolidVolume: uniform density inside a closed, consistently wound surface (exact for the
//    polyhedron: divergence theorem, Mirtich 1996 / Eberly "Polyhedral Mass Properties").
//  - ThinShell: uniform density over the surface area (exact for the triangles as flat plates).
//    Used as the fallback whenever the mesh does not bound a usable volume.
#pragma once

#include "adb/core/geometry.h"
#include "adb/core/mesh.h"

namespace adb {

/// Which mass model produced a MassProperties.
enum class MassModel {
  SolidVolume,  ///< mass uniform in the enclosed volume
  ThinShell,    ///< mass uniform over the surface (also used for the zero-area point mass)
};

/// Mass properties of a mesh for a body of unit mass; multiply `inertia` and
/// `principalMoments` by the body's mass.
struct MassProperties {
  MassModel model = MassModel::ThinShell;  ///< which model produced these numbers
  double volume = 0.0;                     ///< solid: enclosed volume (> 0); shell: 0
  double area = 0.0;                       ///< total area of the non-degenerate triangles
  Vec3 centerOfMass = Vec3::Zero();        ///< in mesh coordinates
  Mat3 inertia = Mat3::Zero();             ///< unit-mass inertia tensor about centerOfMass
  Mat3 principalAxes = Mat3::Identity();   ///< columns: principal axes (rotation, det +1)
  Vec3 principalMoments = Vec3::Zero();    ///< unit-mass moments about the axes, >= 0, ascending
  /// Every edge shared by exactly two consistently wound triangles (see computeMassProperties).
  bool closed = false;
};

/// Mass properties of `mesh` for unit mass.
///
/// Model choice (the fallback rules):
///  1. All triangles degenerate (zero total area): a point mass at bounds().center(); inertia,
///     principal moments, volume and area are 0, axes the identity, model ThinShell.
///  2. `closed` and |signed volume| > 1e-9 * area * bounds diagonal: SolidVolume. An inward-wound
///     closed mesh (negative signed volume) gives the same numbers as the outward one.
///  3. Otherwise (open, inconsistently wound, non-manifold edge, or a closed but flat surface
///     such as a two-sided sheet): ThinShell, mass spread uniformly over the area.
///
/// `closed` is decided on directed edges: every directed edge u->v occurs exactly once and its
/// reverse v->u exactly once. It is tried on the vertex indices first and, if that fails, again
/// with vertices of bit-identical position merged (so an unwelded "triangle soup", as read from
/// STL, still counts as closed). Triangles with a repeated vertex (by index, or by position in
/// the second try) are left out of the edge count; zero-area collinear triangles are counted
/// (they can be what closes a T-junction seam) and add nothing to the volume integrals.
///
/// The result is finite for every valid mesh: integrals are taken relative to the bounds centre
/// and in power-of-two-scaled units, and every division is guarded. Should the final numbers
/// still overflow (coordinates beyond about 1e100), rule 1's point mass is returned.
MassProperties computeMassProperties(const TriangleMesh& mesh);

}  // namespace adb
