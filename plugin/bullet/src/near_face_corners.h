// Internal: the corners of a mesh's root box that face a direction, where a fast body's
// speculative contacts go.
//
// Why corners: a body falling flat, face to face, has hundreds of candidate points at one
// distance, and whichever few a reduction kept lay in one corner of its face; the solver
// stopped that corner only and the body turned about it, through a 4 cm mesh slab at 50 m/s
// and 0.14 to 0.33 into a plane (docs/bullet-budget.md, "Continuous collision detection").
// The four corners of the box's near face, each given the closest distance, hold the face.
#pragma once

#include <LinearMath/btTransform.h>
#include <LinearMath/btVector3.h>

#include <array>

namespace adb {

class MeshShape;

namespace detail {

/// The four corners of `mesh`'s root box (posed by `pose`) farthest along `direction`
/// (world), farthest first: the face the box turns towards it.
std::array<btVector3, 4> nearFaceCorners(const MeshShape& mesh, const btTransform& pose,
                                         const btVector3& direction);

}  // namespace detail
}  // namespace adb
