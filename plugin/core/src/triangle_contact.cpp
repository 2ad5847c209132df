// triangleContact: separating-axis penetration depth over the complete set of candidate axes of
// two triangles, a stability-oriented choice among near-equal axes, and a contact point taken
// from the deepest part of the overlap.
//
// Why the candidate set is complete: for two convex polytopes, the penetration depth (the
// shortest translation that separates them) is the distance from the origin to the boundary of
// their Minkowski difference A - B, i.e. the minimum over its facet normals d of
// max(A.d) - min(B.d). A facet of A - B is the sum of two supporting features whose dimensions
// add up to 2; for two (flat) triangles that is face + vertex (normal +-nA or +-nB) or
// edge + edge (normal +-(e x f)). An in-plane edge normal of a triangle is never a facet normal
// (its supporting feature is an edge, and the other triangle's support in a generic direction
// is a vertex), so it is not needed even for nearly coplanar pairs: there e x f tends to the
// common normal, whose overlap tends to 0. Any axis at all gives a valid separating translation
// (project, then move by the overlap), so skipping an ill-conditioned axis can only make the
// reported depth larger than the minimum, never make the translation fail to separate.
//
// Numerics: the six vertices are translated to the centre of their bounding box and scaled by
// an exact power of two so that the configuration's extent L lies in [1, 2). All tolerances
// are then plain numbers times L, power-of-two scalings of the input are exact, and nothing
// overflows (every product has degree <= 2 in coordinates bounded by 2).
#include "adb/core/triangle_contact.h"

#include "segment_closest_points.h"

#include <cmath>
#include <limits>

namespace adb {
namespace {

constexpr double kUnitRoundoff = 0x1p-53;

// A cross product u x v of local difference vectors (absolute coordinate error ~ u_r L from the
// translation) is trusted as an axis only when |u x v| > kAxisPrecision * L * (|u| + |v|): its
// direction error is then below ~2 u_r / kAxisPrecision ~ 2e-7 rad. This drops faces whose
// smallest height is below ~1e-9 L (they act as their edges) and edge pairs within ~1e-9 rad
// of parallel or with an edge shorter than ~1e-9 L. The other candidates still give a valid
// (at worst slightly deeper) separating translation.
constexpr double kAxisPrecision = 1e-9;

// Edge-edge axes compete with their depth raised by 5 %: ODE's box-box "fudge factor". An edge
// axis whose depth is within a few percent of a face's is almost always a grazing edge that
// flickers with solver noise, while the face normal is stable under small rotations.
constexpr double kEdgeBias = 0.05;

// Candidates whose (biased) depth is within kTieRelative * |best| + kTieAbsolute * L of the
// best are treated as equally deep: the choice among them uses stable keys (face, hint,
// area, winding) instead of depth differences that are rounding or solver noise. The relative
// part also gives hysteresis when the hint is the previous frame's normal. The absolute part is
// far above rounding (~1e-15 L) and far below any physical penetration.
constexpr double kTieRelative = 1e-3;
constexpr double kTieAbsolute = 1e-9;

// The hint fixes an axis's orientation only when |axis . hint| >= kHintOrientCos (about 0.6
// degrees from perpendicular); closer to perpendicular its sign is noise and both orientations
// compete by depth, so a tiny rotation cannot flip the normal.
constexpr double kHintOrientCos = 1e-2;
// Alignments with the hint that differ by less than this are equal (then area decides).
constexpr double kHintTie = 1e-9;

// The prism of the reference face is widened by this times L before clipping, so that a
// touching contact on the prism's wall (which trianglesIntersect accepts within 1e-12 L) is not
// clipped away; the contact point can then lie this far outside the triangle (for B's face,
// outside B), far below anything physical.
constexpr double kClipTolerance = 1e-11;
// Vertices within this times L of the extreme projection form the supporting feature of an
// edge axis (exact ties there are broken only by rounding).
constexpr double kFeatureBand = 1e-9;
// The contact point is the weighted mean of the clipped points within this times L of the
// deepest one (weight 1 at the deepest, falling linearly to 0 at the band): a face that is
// flat within ~1e-4 rad gives the middle of the overlap, not whichever corner rounding makes
// deepest, and the point moves continuously while the tilt grows.
constexpr double kPointBand = 1e-4;
// Two degenerate triangles whose closest points are farther apart than this times L define a
// normal by that difference; closer, the difference is rounding noise (coordinates carry an
// error of ~u_r L).
constexpr double kDistanceNoise = 1024 * kUnitRoundoff;

inline double minOf(double a, double b) { return b < a ? b : a; }
inline double maxOf(double a, double b) { return a < b ? b : a; }

using Tri = Vec3[3];

/// A triangle's face: normal from the two shortest edges (the best conditioned pair).
struct Face {
  Vec3 n = Vec3::Zero();     ///< un-normalised, with the triangle's winding
  Vec3 unit = Vec3::Zero();  ///< n / |n| when usable
  double area2 = 0;          ///< |n| (twice the area)
  bool usable = false;
};

Face makeFace(const Tri& t, double scale) {
  const double l0 = (t[1] - t[0]).squaredNorm(), l1 = (t[2] - t[1]).squaredNorm(),
               l2 = (t[0] - t[2]).squaredNorm();
  const int k = l0 >= l1 ? (l0 >= l2 ? 0 : 2) : (l1 >= l2 ? 1 : 2);
  // Cross product at the vertex opposite the longest edge: same orientation as
  // (t1 - t0) x (t2 - t0) (cyclic shift), smallest rounding error relative to |n|.
  const Vec3& apex = t[(k + 2) % 3];
  const Vec3 u = t[k] - apex, v = t[(k + 1) % 3] - apex;
  Face f;
  f.n = u.cross(v);
  f.area2 = f.n.norm();
  f.usable = f.area2 > kAxisPrecision * scale * (u.norm() + v.norm());
  if (f.usable) f.unit = f.n / f.area2;  // area2 > 0 here
  return f;
}

inline void project(const Tri& t, const Vec3& d, double& lo, double& hi) {
  const double p0 = t[0].dot(d), p1 = t[1].dot(d), p2 = t[2].dot(d);
  lo = minOf(p0, minOf(p1, p2));
  hi = maxOf(p0, maxOf(p1, p2));
}

enum class Kind { FaceA, FaceB, Edge };

struct Candidate {
  Vec3 dir;      ///< unit; B moves along +dir
  double depth;  ///< max(A.dir) - min(B.dir); negative when dir separates
  double rank;   ///< depth, biased for edge axes
  Kind kind;
  bool winding;  ///< the orientation preferred without a hint (A's +n, B's -n, +(e x f))
};

constexpr int kMaxCandidates = 2 * (2 + 9);

struct Candidates {
  Candidate c[kMaxCandidates];
  int count = 0;
};

/// Adds both orientations of the unit axis u, or only the one the hint asks for.
void addAxis(Candidates& set, const Tri& a, const Tri& b, const Vec3& u, Kind kind,
             bool windingPositive, const Vec3* hint) {
  double loA = 0, hiA = 0, loB = 0, hiB = 0;
  project(a, u, loA, hiA);
  project(b, u, loB, hiB);
  bool keepPlus = true, keepMinus = true;
  if (hint != nullptr) {
    const double c = u.dot(*hint);
    if (c >= kHintOrientCos) keepMinus = false;
    if (c <= -kHintOrientCos) keepPlus = false;
  }
  const auto push = [&](const Vec3& d, double depth, bool winding) {
    if (set.count >= kMaxCandidates) return;  // cannot happen: 11 axes at most
    const double rank = kind == Kind::Edge ? depth + kEdgeBias * std::abs(depth) : depth;
    set.c[set.count++] = Candidate{d, depth, rank, kind, winding};
  };
  if (keepPlus) push(u, hiA - loB, windingPositive);
  if (keepMinus) push(-u, hiB - loA, !windingPositive);
}

/// True when x is preferred over y; both are within the tie band and of the same class
/// (faces, or edges).
bool preferred(const Candidate& x, const Candidate& y, const Vec3* hint, double areaA,
               double areaB) {
  if (hint != nullptr) {
    const double hx = x.dir.dot(*hint), hy = y.dir.dot(*hint);
    if (hx > hy + kHintTie) return true;
    if (hy > hx + kHintTie) return false;
  }
  if (x.kind != Kind::Edge && x.kind != y.kind) {
    // Faces of different triangles: the larger triangle's normal is the better conditioned
    // and is invariant under rigid motion; A on an exact tie.
    const double ax = x.kind == Kind::FaceA ? areaA : areaB;
    const double ay = y.kind == Kind::FaceA ? areaA : areaB;
    if (ax != ay) return ax > ay;
    return x.kind == Kind::FaceA;
  }
  if (x.kind == Kind::Edge && x.rank != y.rank) return x.rank < y.rank;
  return x.winding && !y.winding;
}

// ---- Contact point helpers ------------------------------------------------------------------

constexpr int kMaxPolygon = 16;

/// Sutherland-Hodgman clip of triangle t to the prism over `ref` (the three planes through its
/// edges containing its normal n), widened by tol (a distance). Returns the vertex count.
int clipToPrism(const Tri& t, const Tri& ref, const Vec3& n, double tol, Vec3 (&out)[kMaxPolygon]) {
  Vec3 buf[kMaxPolygon];
  int count = 3;
  for (int i = 0; i < 3; ++i) out[i] = t[i];
  for (int k = 0; k < 3 && count > 0; ++k) {
    const Vec3 e = ref[(k + 1) % 3] - ref[k];
    const Vec3 m = n.cross(e);  // inward for the winding that defines n
    const double widen = tol * m.norm();
    int next = 0;
    for (int i = 0; i < count; ++i) buf[i] = out[i];
    for (int i = 0; i < count; ++i) {
      const Vec3& p = buf[i];
      const Vec3& q = buf[(i + 1) % count];
      const double hp = m.dot(p - ref[k]) + widen, hq = m.dot(q - ref[k]) + widen;
      // Rounding can make a nearly degenerate polygon cross a plane more often than a convex
      // one would; the capacity check only drops points, the rest stay on the triangle.
      if (hp >= 0 && next < kMaxPolygon) out[next++] = p;
      if ((hp >= 0) != (hq >= 0) && next < kMaxPolygon) {
        // hp and hq have opposite signs (one of them < 0), so hp - hq != 0.
        out[next++] = p + (q - p) * (hp / (hp - hq));
      }
    }
    count = next;
  }
  return count;
}

/// Weighted mean of the points whose projection on d is within band of the extreme (the
/// largest when `largest`, else the smallest): weight 1 - distance / band.
Vec3 deepestMean(const Vec3* p, int count, const Vec3& d, bool largest, double band) {
  double extreme =
      largest ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
  for (int i = 0; i < count; ++i) {
    const double s = p[i].dot(d);
    extreme = largest ? maxOf(extreme, s) : minOf(extreme, s);
  }
  Vec3 sum = Vec3::Zero();
  double weights = 0;
  for (int i = 0; i < count; ++i) {
    const double gap = largest ? extreme - p[i].dot(d) : p[i].dot(d) - extreme;
    const double w = maxOf(0.0, 1.0 - gap / band);  // band > 0
    sum += w * p[i];
    weights += w;
  }
  return weights > 0 ? Vec3(sum / weights) : p[0];  // the extreme point has weight 1
}

/// The supporting feature of t along d (largest projections when `largest`, else smallest) as
/// a segment: one vertex (p == q), an edge, or the two farthest vertices when all three are
/// within the band (a degenerate triangle).
void supportSegment(const Tri& t, const Vec3& d, bool largest, double band, Vec3& p, Vec3& q) {
  double s[3];
  for (int i = 0; i < 3; ++i) s[i] = largest ? t[i].dot(d) : -t[i].dot(d);
  const double top = maxOf(s[0], maxOf(s[1], s[2]));
  int idx[3];
  int n = 0;
  for (int i = 0; i < 3; ++i) {
    if (s[i] >= top - band) idx[n++] = i;
  }
  p = t[idx[0]];  // n >= 1: the maximum itself is always selected
  q = p;
  if (n == 2) {
    q = t[idx[1]];
  } else if (n == 3) {
    const double l0 = (t[1] - t[0]).squaredNorm(), l1 = (t[2] - t[1]).squaredNorm(),
                 l2 = (t[0] - t[2]).squaredNorm();
    const int k = l0 >= l1 ? (l0 >= l2 ? 0 : 2) : (l1 >= l2 ? 1 : 2);
    p = t[k];
    q = t[(k + 1) % 3];
  }
}

/// Longest edge of t as a segment (a point when all vertices coincide).
void longestEdge(const Tri& t, Vec3& p, Vec3& q) {
  const double l0 = (t[1] - t[0]).squaredNorm(), l1 = (t[2] - t[1]).squaredNorm(),
               l2 = (t[0] - t[2]).squaredNorm();
  const int k = l0 >= l1 ? (l0 >= l2 ? 0 : 2) : (l1 >= l2 ? 1 : 2);
  p = t[k];
  q = t[(k + 1) % 3];
}

/// The contact in local coordinates (translated and power-of-two scaled, extent in [1, 2)).
struct LocalContact {
  Vec3 pointOnB = Vec3::Zero();
  Vec3 normal = Vec3::Zero();
  double depth = 0;
  bool valid = false;
};

LocalContact contactLocal(const Tri& a, const Tri& b, const Vec3* hint, double scale) {
  LocalContact out;
  const Face fa = makeFace(a, scale), fb = makeFace(b, scale);

  Candidates set;
  if (fa.usable) addAxis(set, a, b, fa.unit, Kind::FaceA, true, hint);
  // B moves along -nB when B's front faces A, so -nB is B's winding orientation.
  if (fb.usable) addAxis(set, a, b, fb.unit, Kind::FaceB, false, hint);
  for (int i = 0; i < 3; ++i) {
    const Vec3 e = a[(i + 1) % 3] - a[i];
    const double le = e.norm();
    for (int j = 0; j < 3; ++j) {
      const Vec3 f = b[(j + 1) % 3] - b[j];
      const Vec3 c = e.cross(f);
      const double lc = c.norm();
      if (lc > kAxisPrecision * scale * (le + f.norm())) {
        addAxis(set, a, b, c / lc, Kind::Edge, true, hint);
      }
    }
  }

  if (set.count == 0) {
    // Both degenerate with no usable edge pair: parallel segments, or points.
    Vec3 pa, qa, pb, qb, ca, cb;
    longestEdge(a, pa, qa);
    longestEdge(b, pb, qb);
    detail::closestSegmentPoints(pa, qa, pb, qb, ca, cb);
    const Vec3 gap = cb - ca;
    const double dist = gap.norm();
    Vec3 d;
    if (dist > kDistanceNoise * scale) {
      d = gap / dist;
    } else if (hint != nullptr) {
      d = *hint;
    } else {
      return out;  // no direction is defined: valid = false
    }
    double loA = 0, hiA = 0, loB = 0, hiB = 0;
    project(a, d, loA, hiA);
    project(b, d, loB, hiB);
    out.pointOnB = cb;
    out.normal = d;
    out.depth = maxOf(0.0, hiA - loB);
    out.valid = true;
    return out;
  }

  double best = set.c[0].rank;
  for (int i = 1; i < set.count; ++i) best = minOf(best, set.c[i].rank);
  const double limit = best + kTieRelative * std::abs(best) + kTieAbsolute * scale;
  bool anyFace = false;
  for (int i = 0; i < set.count; ++i) {
    anyFace = anyFace || (set.c[i].rank <= limit && set.c[i].kind != Kind::Edge);
  }
  int chosen = -1;
  for (int i = 0; i < set.count; ++i) {
    const Candidate& c = set.c[i];
    if (c.rank > limit || (anyFace && c.kind == Kind::Edge)) continue;
    if (chosen < 0 || preferred(c, set.c[chosen], hint, fa.area2, fb.area2)) chosen = i;
  }
  const Candidate& win = set.c[chosen];  // the best-ranked candidate is always eligible
  out.normal = win.dir;
  out.depth = maxOf(0.0, win.depth);
  out.valid = true;

  Vec3 poly[kMaxPolygon];
  const double band = kPointBand * scale;
  if (win.kind == Kind::FaceA) {
    // B's part over A, deepest along -normal (B's support, which sits depth below A's).
    int n = clipToPrism(b, a, fa.n, kClipTolerance * scale, poly);
    if (n == 0) {
      for (int i = 0; i < 3; ++i) poly[i] = b[i];
      n = 3;
    }
    out.pointOnB = deepestMean(poly, n, win.dir, false, band);
  } else if (win.kind == Kind::FaceB) {
    // A's part over B, deepest along +normal, then dropped onto B's plane.
    int n = clipToPrism(a, b, fb.n, kClipTolerance * scale, poly);
    if (n == 0) {
      for (int i = 0; i < 3; ++i) poly[i] = a[i];
      n = 3;
    }
    const Vec3 onA = deepestMean(poly, n, win.dir, true, band);
    const Vec3 centroidB = (b[0] + b[1] + b[2]) / 3.0;
    out.pointOnB = onA - (onA - centroidB).dot(win.dir) * win.dir;
  } else {
    Vec3 pa, qa, pb, qb, ca, cb;
    supportSegment(a, win.dir, true, kFeatureBand * scale, pa, qa);
    supportSegment(b, win.dir, false, kFeatureBand * scale, pb, qb);
    detail::closestSegmentPoints(pa, qa, pb, qb, ca, cb);
    out.pointOnB = cb;
  }
  return out;
}

}  // namespace

TriangleContact triangleContact(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                                const Vec3& b1, const Vec3& b2, const Vec3& hintNormal) {
  TriangleContact result;
  const Vec3* in[6] = {&a0, &a1, &a2, &b0, &b1, &b2};
  for (const Vec3* p : in) {
    if (!p->allFinite()) return result;
  }

  Vec3 lo = a0, hi = a0;
  for (const Vec3* p : in) {
    lo = lo.cwiseMin(*p);
    hi = hi.cwiseMax(*p);
  }
  // Coordinates near DBL_MAX: their differences can overflow; an exact pre-scale by 1/4 avoids
  // it (and the subtraction of the centre below then cannot overflow either).
  const double pre = (hi - lo).allFinite() ? 1.0 : 0.25;
  const Vec3 centre = 0.5 * (pre * lo + pre * hi);
  const double extent = (pre * hi - pre * lo).maxCoeff();
  // Scale by 2^-e so that the extent lies in [1, 2): exact (ldexp), also for subnormal extents.
  const int e = extent > 0 ? std::ilogb(extent) : 0;
  const auto local = [&](const Vec3& x) -> Vec3 {
    const Vec3 d = pre * x - centre;
    return Vec3(std::ldexp(d.x(), -e), std::ldexp(d.y(), -e), std::ldexp(d.z(), -e));
  };
  const Tri a = {local(a0), local(a1), local(a2)};
  const Tri b = {local(b0), local(b1), local(b2)};
  const double scale = extent > 0 ? std::ldexp(extent, -e) : 1.0;

  // Normalise the hint through its largest component first, so that tiny or huge hints do not
  // underflow or overflow in the squared norm.
  Vec3 hint = Vec3::Zero();
  bool hasHint = false;
  const double hmax = hintNormal.cwiseAbs().maxCoeff();
  if (std::isfinite(hmax) && hmax > 0) {
    hint = (hintNormal / hmax).normalized();
    hasHint = true;
  }

  const LocalContact c = contactLocal(a, b, hasHint ? &hint : nullptr, scale);
  const auto world = [&](const Vec3& x) -> Vec3 {
    const Vec3 s(std::ldexp(x.x(), e), std::ldexp(x.y(), e), std::ldexp(x.z(), e));
    return (s + centre) / pre;
  };
  if (!c.valid) {
    // No direction: report B's centroid, zero normal and depth.
    result.pointOnB = world((b[0] + b[1] + b[2]) / 3.0);
    return result;
  }
  result.pointOnB = world(c.pointOnB);
  result.normal = c.normal;
  const double depth = std::ldexp(c.depth, e) / pre;
  // Only an extent near DBL_MAX can overflow here; keep the output finite.
  result.depth = std::isfinite(depth) ? depth : std::numeric_limits<double>::max();
  result.valid = true;
  return result;
}

}  // namespace adb
