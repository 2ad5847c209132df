// Sphere, capsule and box against one triangle, in closed form.
#include "adb/core/primitive_contact.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "segment_closest_points.h"

namespace adb {
namespace {

// Contacts of one capsule and one triangle kept together push within 60 degrees (cosine) of
// the deepest one: two that push against each other only squeeze the capsule.
constexpr double kSameWay = 0.5;
// Edge-edge axes compete with a 5 % handicap, as in ODE and triangleContact: a box resting
// on a face must not flicker to an edge axis of nearly the same depth.
constexpr double kEdgeHandicap = 0.05;
// A capsule's axis crossing a triangle's plane counts as through the triangle within this
// fraction of its size: an axis through a shared edge is through both triangles.
constexpr double kInsideTolerance = 1e-9;

// Unit normal of (a, b, c), or zero for a degenerate triangle.
Vec3 unitNormal(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double length = n.norm();
  return length > 0.0 && std::isfinite(length) ? Vec3(n / length) : Vec3::Zero();
}

// Closest point of segment pq to x.
Vec3 closestOnSegment(const Vec3& x, const Vec3& p, const Vec3& q) {
  const Vec3 d = q - p;
  const double dd = d.squaredNorm();
  if (!(dd > 0.0)) return p;
  return p + std::clamp((x - p).dot(d) / dd, 0.0, 1.0) * d;
}

// Whether x, on the plane of (a, b, c) with unnormalised normal n, lies in the triangle
// (edge functions, with a tolerance relative to the triangle's size).
bool insideTriangle(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& n) {
  const double tolerance = -kInsideTolerance * n.squaredNorm();
  return (b - a).cross(x - a).dot(n) >= tolerance && (c - b).cross(x - b).dot(n) >= tolerance &&
         (a - c).cross(x - c).dot(n) >= tolerance;
}

// A sphere-like contact: a point at distance `radius` around x against the triangle.
void pointContact(const Vec3& x, double radius, const Vec3& a, const Vec3& b, const Vec3& c,
                  double reach, PrimitiveContacts& out) {
  const Vec3 q = closestPointOnTriangle(x, a, b, c);
  const Vec3 v = x - q;
  const double distance = v.norm();
  if (!(distance - radius <= reach) || !std::isfinite(distance)) return;  // also refuses NaN
  Vec3 normal = distance > 0.0 ? Vec3(v / distance) : unitNormal(a, b, c);
  if (normal.isZero()) normal = Vec3::UnitZ();  // a point on a degenerate triangle
  out.add(q, normal, distance - radius);
}

// The capsule axis's closest point to the triangle's edges, when it is not an end (the ends
// are point contacts of their own).
void axisEdgeContact(const Vec3& p0, const Vec3& p1, double radius, const Vec3& a,
                     const Vec3& b, const Vec3& c, double reach, PrimitiveContacts& out) {
  Vec3 onAxis = p0, onTriangle = a;
  double best = std::numeric_limits<double>::infinity();
  const Vec3* corners[3] = {&a, &b, &c};
  for (int e = 0; e < 3; ++e) {
    Vec3 s, t;
    detail::closestSegmentPoints(p0, p1, *corners[e], *corners[(e + 1) % 3], s, t);
    const double d = (s - t).squaredNorm();
    if (d < best) {
      best = d;
      onAxis = s;
      onTriangle = t;
    }
  }
  const double length2 = (p1 - p0).squaredNorm();
  const double endTolerance = 1e-12 * length2;
  if ((onAxis - p0).squaredNorm() <= endTolerance || (onAxis - p1).squaredNorm() <= endTolerance) {
    return;
  }
  const double distance = std::sqrt(best);
  if (!(distance - radius <= reach) || !(distance > 0.0)) return;
  out.add(onTriangle, (onAxis - onTriangle) / distance, distance - radius);
}

}  // namespace

Vec3 closestPointOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return b;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return c;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0) return a + (d1 / (d1 - d3)) * ab;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0) {
    return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  }
  const double sum = va + vb + vc;
  if (sum > 0.0 && std::isfinite(sum)) return a + ab * (vb / sum) + ac * (vc / sum);
  // Degenerate (collinear or coincident corners): the closest of its edges' points.
  Vec3 best = closestOnSegment(p, a, b);
  for (const Vec3& q : {closestOnSegment(p, b, c), closestOnSegment(p, c, a)}) {
    if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
  }
  return best;
}

bool triangleNearBox(const Vec3& a, const Vec3& b, const Vec3& c, const OrientedBox& box,
                     double reach) {
  const Vec3 la = box.axes.transpose() * (a - box.centre);
  const Vec3 lb = box.axes.transpose() * (b - box.centre);
  const Vec3 lc = box.axes.transpose() * (c - box.centre);
  for (int k = 0; k < 3; ++k) {
    const double lo = std::min({la[k], lb[k], lc[k]}), hi = std::max({la[k], lb[k], lc[k]});
    if (lo > box.half[k] + reach || hi < -box.half[k] - reach) return false;
  }
  const Vec3 n = unitNormal(la, lb, lc);
  return std::abs(n.dot(la)) <= n.cwiseAbs().dot(box.half) + reach;
}

void sphereTriangleContacts(const Vec3& centre, double radius, const Vec3& a, const Vec3& b,
                            const Vec3& c, double reach, PrimitiveContacts& out) {
  if (!std::isfinite(radius) || radius < 0.0) return;
  pointContact(centre, radius, a, b, c, reach, out);
}

void capsuleTriangleContacts(const Vec3& p0, const Vec3& p1, double radius, const Vec3& a,
                             const Vec3& b, const Vec3& c, double reach,
                             PrimitiveContacts& out) {
  if (!std::isfinite(radius) || radius < 0.0) return;
  const Vec3 n = (b - a).cross(c - a);
  const double s0 = n.dot(p0 - a), s1 = n.dot(p1 - a);
  if ((s0 < 0.0 && s1 > 0.0) || (s0 > 0.0 && s1 < 0.0)) {
    // The axis crosses the triangle's plane: through the triangle, the capsule is pushed out
    // along the normal, towards the side of its longer part. That one contact only: an end
    // contact on the shorter side would push the other way.
    const Vec3 x = p0 + (s0 / (s0 - s1)) * (p1 - p0);
    if (insideTriangle(x, a, b, c, n)) {
      const Vec3 unit = unitNormal(a, b, c);
      const double d0 = std::abs(unit.dot(p0 - a)), d1 = std::abs(unit.dot(p1 - a));
      const Vec3 normal = (d0 >= d1) == (s0 > 0.0) ? unit : Vec3(-unit);
      out.add(x, normal, -std::min(d0, d1) - radius);
      return;
    }
  }
  // Otherwise: each end within reach of the triangle (a capsule lying on a face rests on two
  // points) and the axis's closest point to an edge, kept only where they push within 60
  // degrees of the deepest of them (an axis crossing the plane beside the triangle has its
  // ends on both sides, their normals 110 degrees apart).
  PrimitiveContacts found;
  pointContact(p0, radius, a, b, c, reach, found);
  pointContact(p1, radius, a, b, c, reach, found);
  axisEdgeContact(p0, p1, radius, a, b, c, reach, found);
  int deepest = -1;
  for (int i = 0; i < found.count; ++i) {
    if (deepest < 0 || found.points[i].separation < found.points[deepest].separation) deepest = i;
  }
  if (deepest < 0) return;
  const Vec3 normal = found.points[deepest].normal;
  for (int i = 0; i < found.count; ++i) {
    if (i == deepest || found.points[i].normal.dot(normal) > kSameWay) {
      out.add(found.points[i].onTriangle, found.points[i].normal, found.points[i].separation);
    }
  }
}


namespace {

// The separating axis of a box (axis-aligned in its own frame, half extents h) and a
// triangle v: the box-to-triangle direction of least penetration (or largest gap).
struct BoxAxis {
  enum Kind { BoxFace, TriangleFace, EdgeEdge } kind = BoxFace;
  Vec3 normal = Vec3::Zero();  // unit, from the box towards the triangle
  double separation = -std::numeric_limits<double>::infinity();
  int boxAxis = 0, triangleEdge = 0;
};

// An axis whose cosine with the push hint is above this (about 0.6 degrees from
// perpendicular) is taken in the hint's orientation only; as triangleContact's hint rule.
constexpr double kHintCosine = 0.01;

// Separation of box and triangle along unit axis l, and the direction it points (the way
// the triangle is pushed); `hint` (unit or zero) fixes that direction unless nearly
// perpendicular to l.
void testAxis(const Vec3& l, const Vec3& h, const Vec3 v[3], const Vec3& hint,
              BoxAxis::Kind kind, int boxAxis, int edge, double handicap, BoxAxis& best) {
  const double rb = h.dot(l.cwiseAbs());
  const double t0 = l.dot(v[0]), t1 = l.dot(v[1]), t2 = l.dot(v[2]);
  const double tmin = std::min({t0, t1, t2}), tmax = std::max({t0, t1, t2});
  const double plus = tmin - rb, minus = -tmax - rb;
  const double along = hint.dot(l);
  const bool positive = along > kHintCosine ? true : along < -kHintCosine ? false : plus >= minus;
  const double separation = positive ? plus : minus;
  if (!(separation - handicap > best.separation)) return;
  best.kind = kind;
  best.normal = positive ? l : Vec3(-l);
  best.separation = separation;
  best.boxAxis = boxAxis;
  best.triangleEdge = edge;
}

// The deepest axis; stops early (with that axis) once one separates them beyond `reach`:
// most triangles near a box are not touching it, and the 9 edge axes cost the most.
BoxAxis deepestAxis(const Vec3& h, const Vec3 v[3], const Vec3& n, const Vec3& hint,
                    double reach) {
  BoxAxis best;
  for (int k = 0; k < 3; ++k) {
    testAxis(Vec3::Unit(k), h, v, hint, BoxAxis::BoxFace, k, 0, 0.0, best);
    if (best.separation > reach) return best;
  }
  const double nLength = n.norm();
  if (nLength > 0.0) {
    testAxis(n / nLength, h, v, hint, BoxAxis::TriangleFace, 0, 0, 0.0, best);
    if (best.separation > reach) return best;
  }
  for (int e = 0; e < 3; ++e) {
    const Vec3 edge = v[(e + 1) % 3] - v[e];
    const double edgeLength = edge.norm();
    for (int k = 0; k < 3; ++k) {
      const Vec3 l = Vec3::Unit(k).cross(edge);
      const double length = l.norm();
      // Nearly parallel to a box axis: the direction would be rounding.
      if (!(length > 1e-9 * edgeLength)) continue;
      const Vec3 unit = l / length;
      testAxis(unit, h, v, hint, BoxAxis::EdgeEdge, k, e,
               kEdgeHandicap * std::abs(best.separation), best);
      if (best.separation > reach) return best;
    }
  }
  return best;
}

// A convex polygon of at most kMaxPolygon corners, clipped in place.
constexpr int kMaxPolygon = 8;  // a triangle cut by 4 planes, or a quad by 3: at most 7
struct Polygon {
  Vec3 corners[kMaxPolygon];
  int count = 0;
};

// Keeps the part of `polygon` where normal . x <= offset (Sutherland-Hodgman). A polygon
// wholly inside is left as it is: against a large box face, most triangles are.
void clip(Polygon& polygon, const Vec3& normal, double offset) {
  double side[kMaxPolygon];
  bool inside = true;
  for (int i = 0; i < polygon.count; ++i) {
    side[i] = normal.dot(polygon.corners[i]) - offset;
    inside = inside && side[i] <= 0.0;
  }
  if (inside) return;
  Polygon out;
  for (int i = 0; i < polygon.count; ++i) {
    const int next = (i + 1) % polygon.count;
    const double dp = side[i], dq = side[next];
    const Vec3& p = polygon.corners[i];
    if (dp <= 0.0 && out.count < kMaxPolygon) out.corners[out.count++] = p;
    if ((dp < 0.0 && dq > 0.0) || (dp > 0.0 && dq < 0.0)) {
      const Vec3& q = polygon.corners[next];
      if (out.count < kMaxPolygon) out.corners[out.count++] = p + (dp / (dp - dq)) * (q - p);
    }
  }
  polygon = out;
}

// Adds the deepest kMaxPrimitiveContacts of the candidate points (at most kMaxPolygon).
void addDeepest(PrimitiveContact* found, int count, PrimitiveContacts& out) {
  for (int i = 1; i < count; ++i) {  // insertion sort: a handful of points
    for (int j = i; j > 0 && found[j].separation < found[j - 1].separation; --j) {
      std::swap(found[j], found[j - 1]);
    }
  }
  for (int i = 0; i < count; ++i) out.add(found[i].onTriangle, found[i].normal, found[i].separation);
}

// Triangle face axis: the box's face towards the triangle, clipped to the triangle's prism;
// its corners within reach of the triangle's plane.
void boxFaceOverTriangle(const Vec3& h, const Vec3 v[3], const Vec3& n, const BoxAxis& axis,
                         double reach, PrimitiveContacts& out) {
  int k = 0;
  for (int j = 1; j < 3; ++j) {
    if (std::abs(axis.normal[j]) > std::abs(axis.normal[k])) k = j;
  }
  const int i1 = (k + 1) % 3, i2 = (k + 2) % 3;
  Polygon face;
  for (const auto& [s1, s2] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
    Vec3 corner;
    corner[k] = axis.normal[k] >= 0.0 ? h[k] : -h[k];
    corner[i1] = s1 * h[i1];
    corner[i2] = s2 * h[i2];
    face.corners[face.count++] = corner;
  }
  for (int e = 0; e < 3 && face.count > 0; ++e) {
    // The side plane through edge e, its normal pointing out of the triangle.
    const Vec3 side = (v[(e + 1) % 3] - v[e]).cross(n);
    clip(face, side, side.dot(v[e]));
  }
  const double offset = axis.normal.dot(v[0]);
  PrimitiveContact found[kMaxPolygon];
  int count = 0;
  for (int i = 0; i < face.count; ++i) {
    const double separation = offset - axis.normal.dot(face.corners[i]);
    if (separation <= reach) {
      found[count++] = {face.corners[i] + separation * axis.normal, -axis.normal, separation};
    }
  }
  addDeepest(found, count, out);
}

// Box face axis: the triangle clipped to the face's side slabs; its corners within reach.
void triangleOverBoxFace(const Vec3& h, const Vec3 v[3], const BoxAxis& axis, double reach,
                         PrimitiveContacts& out) {
  const int k = axis.boxAxis;
  Polygon polygon;
  for (int i = 0; i < 3; ++i) polygon.corners[polygon.count++] = v[i];
  for (int j = 0; j < 3 && polygon.count > 0; ++j) {
    if (j == k) continue;
    clip(polygon, Vec3::Unit(j), h[j]);
    clip(polygon, -Vec3::Unit(j), h[j]);
  }
  PrimitiveContact found[kMaxPolygon];
  int count = 0;
  for (int i = 0; i < polygon.count; ++i) {
    const double separation = axis.normal.dot(polygon.corners[i]) - h[k];
    if (separation <= reach) found[count++] = {polygon.corners[i], -axis.normal, separation};
  }
  addDeepest(found, count, out);
}

// The box's corner furthest along d.
Vec3 supportCorner(const Vec3& h, const Vec3& d) {
  return Vec3(d.x() >= 0 ? h.x() : -h.x(), d.y() >= 0 ? h.y() : -h.y(),
              d.z() >= 0 ? h.z() : -h.z());
}

}  // namespace

void boxTriangleContacts(const OrientedBox& box, const Vec3& a, const Vec3& b, const Vec3& c,
                         double reach, PrimitiveContacts& out, const Vec3& pushHint) {
  // In the box's frame the box is [-half, half].
  const Mat3 toBox = box.axes.transpose();
  const Vec3 v[3] = {toBox * (a - box.centre), toBox * (b - box.centre), toBox * (c - box.centre)};
  if (!(v[0].allFinite() && v[1].allFinite() && v[2].allFinite())) return;
  const Vec3 h = box.half;
  if (!h.allFinite() || (h.array() < 0.0).any()) return;
  const Vec3 n = (v[1] - v[0]).cross(v[2] - v[0]);
  BoxAxis axis = deepestAxis(h, v, n, Vec3::Zero(), reach);
  // The plain axis pushes the triangle against the way its body was pushed out last step:
  // the body went more than halfway into a thin box. Pushed back out the way it came in
  // while it is not through (its depth that way is less than the box is thick there); a
  // triangle at the far side of a hole the box sits in is farther than that, and keeps the
  // plain axis. The hint is made unit only then: most triangles agree with it.
  const Vec3 hint = toBox * pushHint;
  if (axis.normal.dot(hint) < 0.0) {
    const Vec3 unit = hint / hint.norm();  // not zero: the dot product is negative
    if (unit.allFinite() && axis.normal.dot(unit) < -kHintCosine) {
      const BoxAxis back = deepestAxis(h, v, n, unit, reach);
      if (-back.separation < 2.0 * h.dot(back.normal.cwiseAbs())) axis = back;
    }
  }
  if (!(axis.separation <= reach)) return;
  PrimitiveContacts local;
  if (axis.kind == BoxAxis::TriangleFace) {
    boxFaceOverTriangle(h, v, n, axis, reach, local);
  } else if (axis.kind == BoxAxis::BoxFace) {
    triangleOverBoxFace(h, v, axis, reach, local);
  } else {
    // Edge against edge: the box edge along the axis's box direction, through the corner
    // furthest towards the triangle, against the triangle's edge.
    const int k = axis.boxAxis;
    Vec3 corner = supportCorner(h, axis.normal);
    corner[k] = 0.0;
    const Vec3 boxEnd0 = corner - h[k] * Vec3::Unit(k), boxEnd1 = corner + h[k] * Vec3::Unit(k);
    Vec3 onBox, onTriangle;
    detail::closestSegmentPoints(boxEnd0, boxEnd1, v[axis.triangleEdge],
                                 v[(axis.triangleEdge + 1) % 3], onBox, onTriangle);
    local.add(onTriangle, -axis.normal, axis.separation);
  }
  if (local.count == 0) {
    // Clipping left nothing within reach (rounding at a touching edge): the triangle's
    // point nearest the box's deepest corner.
    const Vec3 deepest = supportCorner(h, axis.normal);
    local.add(closestPointOnTriangle(deepest, v[0], v[1], v[2]), -axis.normal, axis.separation);
  }
  for (int i = 0; i < local.count; ++i) {
    const PrimitiveContact& p = local.points[i];
    out.add(box.centre + box.axes * p.onTriangle, box.axes * p.normal, p.separation);
  }
}

}  // namespace adb
