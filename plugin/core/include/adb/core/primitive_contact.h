// Contacts of a sphere, a capsule or a box with one triangle, in closed form: the
// mesh-versus-primitive tests of a physics engine's narrow phase. Bullet answers each of
// these with GJK (and EPA when they overlap) per triangle, about 20 times the cost.
//
// Every routine works in one frame (the caller's: for a mesh, its tree's local frame keeps
// the numbers small), reports the triangle's side of each contact and reports nothing when
// the shapes are farther apart than `reach`. Triangles are two-sided, as Bullet's are.
#pragma once

#include <cstdint>

#include "adb/core/geometry.h"

namespace adb {

/// A contact between a primitive and a triangle.
struct PrimitiveContact {
  Vec3 onTriangle = Vec3::Zero();  ///< a point on the triangle
  Vec3 normal = Vec3::Zero();      ///< unit, from the triangle towards the primitive
  double separation = 0.0;         ///< signed distance along normal: < 0 penetrating
};

/// Up to this many contacts per primitive and triangle (a box face on a triangle: its 4
/// corners, or the triangle's 3 corners on a box face).
constexpr int kMaxPrimitiveContacts = 4;

/// The contacts a primitive-triangle test found: a fixed buffer, no allocation.
struct PrimitiveContacts {
  PrimitiveContact points[kMaxPrimitiveContacts];
  int count = 0;
  void add(const Vec3& onTriangle, const Vec3& normal, double separation) {
    if (count < kMaxPrimitiveContacts) points[count++] = {onTriangle, normal, separation};
  }
};

/// The point of triangle (a, b, c) closest to p (Ericson, Real-Time Collision Detection
/// 5.1.5). Degenerate triangles included: the result is always one of its points.
Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

/// Whether triangle (a, b, c) and `box` may be closer than `reach`: the box's three face
/// axes and the triangle's normal (a conservative filter, no false negatives).
bool triangleNearBox(const Vec3& a, const Vec3& b, const Vec3& c, const OrientedBox& box,
                     double reach);

/// A sphere against a triangle: one contact when they are closer than `reach`.
void sphereTriangleContacts(const Vec3& centre, double radius, const Vec3& a, const Vec3& b,
                            const Vec3& c, double reach, PrimitiveContacts& out);

/// A capsule (segment p0p1 swept by `radius`) against a triangle: a contact at each end of
/// the segment that is within reach (a capsule lying on a face rests on two points), and one
/// at the segment's closest point when that is neither end.
void capsuleTriangleContacts(const Vec3& p0, const Vec3& p1, double radius, const Vec3& a,
                             const Vec3& b, const Vec3& c, double reach,
                             PrimitiveContacts& out);

/// A box against a triangle by the separating axis theorem over the 13 candidate axes (3
/// box faces, the triangle's normal, 9 edge-edge products). The deepest axis decides the
/// normal; contacts are the corners of the box's face clipped to the triangle (triangle
/// face axis), of the triangle clipped to the box's face (box face axis), or the two edges'
/// closest points (edge-edge); the deepest 4 within reach.
///
/// `pushHint`, in the frame of the triangle and `box` (any length; zero for none): the
/// direction the triangle's body was pushed out of the box last step. Where the deepest axis
/// would push the triangle against it, the axes are tried again, each only in the
/// orientation that agrees with the hint (unless within about 0.6 degrees of perpendicular
/// to it), and that answer is taken while the triangle is less deep that way than the box is
/// thick: a body pressed more than halfway into a thin box (a floor) is pushed back out
/// through the face it came in by, not on through the other one.
void boxTriangleContacts(const OrientedBox& box, const Vec3& a, const Vec3& b, const Vec3& c,
                         double reach, PrimitiveContacts& out,
                         const Vec3& pushHint = Vec3::Zero());

}  // namespace adb
