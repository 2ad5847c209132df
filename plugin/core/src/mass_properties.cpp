// computeMassProperties: one pass over the triangles accumulates both the solid (signed
// tetrahedra against a reference point) and the thin-shell (area-weighted plates) integrals;
// a directed-edge count decides whether the solid model applies.
#include "adb/core/mass_properties.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

namespace adb {
namespace {

// A closed mesh counts as a solid only when |signed volume| exceeds this fraction of
// area * bounds diagonal. The rounding error of the signed volume is bounded by a few ulps of
// sum |a_i| |n_i| / 6 <= diagonal * area / 3 (see accumulate()), so 1e-9 sits about six orders
// of magnitude above the noise while a genuinely thin solid (a 1 x 1 x t plate) is still a solid
// down to t of about 3e-9. Measuring against area * diagonal rather than diagonal^3 keeps small
// bodies far apart from each other (bounds much larger than the volume) solid.
constexpr double kFlatVolumeFraction = 1e-9;

// Bound on the power-of-two scale exponent e: 2^e and 2^-e must both be finite, normal doubles
// (frexp of a subnormal half-extent would otherwise ask for 2^1030 = infinity).
constexpr int kMaxScaleExponent = 1020;

// ---------------------------------------------------------------------------------------------
// Closedness: directed edges

std::uint64_t edgeKey(std::uint32_t from, std::uint32_t to) {
  return (static_cast<std::uint64_t>(from) << 32) | to;
}

// True when every directed edge occurs exactly once and its reverse exactly once. `id` maps a
// vertex index to the identity used for the edges (itself, or a welded representative).
// Triangles with a repeated identity are skipped: their edges a->b, b->a would pair with each
// other and say nothing about the surface.
template <class Id>
bool directedEdgesPairUp(const std::vector<Triangle>& triangles, Id&& id) {
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * triangles.size());
  for (const Triangle& t : triangles) {
    const std::uint32_t a = id(t[0]), b = id(t[1]), c = id(t[2]);
    if (a == b || b == c || a == c) continue;
    edges.push_back(edgeKey(a, b));
    edges.push_back(edgeKey(b, c));
    edges.push_back(edgeKey(c, a));
  }
  if (edges.empty()) return false;  // nothing but repeated-vertex triangles: no surface at all
  // Sorting then binary search is O(n log n) with one allocation; a hash map would allocate
  // per edge.
  std::sort(edges.begin(), edges.end());
  if (std::adjacent_find(edges.begin(), edges.end()) != edges.end()) return false;
  for (const std::uint64_t e : edges) {
    const auto from = static_cast<std::uint32_t>(e >> 32);
    const auto to = static_cast<std::uint32_t>(e & 0xffffffffu);
    if (!std::binary_search(edges.begin(), edges.end(), edgeKey(to, from))) return false;
  }
  return true;
}

struct PositionHash {
  std::size_t operator()(const Vec3& p) const {
    const std::hash<double> h;
    std::size_t seed = h(p.x());
    seed ^= h(p.y()) + 0x9e3779b97f4a7c15ull + (seed << 6) + (seed >> 2);
    seed ^= h(p.z()) + 0x9e3779b97f4a7c15ull + (seed << 6) + (seed >> 2);
    return seed;
  }
};

// For each vertex, the first vertex with a bit-identical position (-0.0 taken as +0.0). Exact
// equality only: welding with a tolerance could join vertices the author meant to keep apart.
std::vector<std::uint32_t> weldIdenticalPositions(const std::vector<Vec3>& vertices) {
  std::vector<std::uint32_t> rep(vertices.size());
  std::unordered_map<Vec3, std::uint32_t, PositionHash> first;
  first.reserve(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    // Adding +0.0 turns -0.0 into +0.0 (they compare equal but hash differently).
    const Vec3 key = vertices[i] + Vec3::Zero();
    rep[i] = first.emplace(key, static_cast<std::uint32_t>(i)).first->second;
  }
  return rep;
}

bool isClosed(const TriangleMesh& mesh) {
  const auto& triangles = mesh.triangles();
  if (directedEdgesPairUp(triangles, [](std::uint32_t v) { return v; })) return true;
  // Index-first keeps bodies that touch (merged parts sharing positions but not indices)
  // closed; the welded retry accepts unwelded soups.
  const std::vector<std::uint32_t> rep = weldIdenticalPositions(mesh.vertices());
  return directedEdgesPairUp(triangles, [&rep](std::uint32_t v) { return rep[v]; });
}

// ---------------------------------------------------------------------------------------------
// Integrals

// Raw sums in scaled coordinates x = (p - reference) * 2^-e, so |x| <= 1 per axis: no
// overflow or underflow in the cubic and fifth-power terms whatever the mesh's scale, and no
// cancellation against a far-away origin. Powers of two make the scaling exact.
struct Sums {
  // Solid: signed tetrahedra (reference, a, b, c) with det = a . ((b - a) x (c - a)).
  double det = 0.0;                       // 6 * volume
  Vec3 detFirst = Vec3::Zero();           // 24 * first moment
  Mat3 detSecond = Mat3::Zero();          // 120 * second moment (integral of x x^T)
  // Shell: w = |(b - a) x (c - a)| = 2 * triangle area, non-degenerate triangles only.
  double w = 0.0;                         // 2 * area
  Vec3 wFirst = Vec3::Zero();             // 6 * first moment
  Mat3 wSecond = Mat3::Zero();            // 24 * second moment
};

Sums accumulate(const TriangleMesh& mesh, const Vec3& reference, double invScale) {
  Sums s;
  const auto& v = mesh.vertices();
  const auto& triangles = mesh.triangles();
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const Triangle& t = triangles[i];
    const Vec3 a = (v[t[0]] - reference) * invScale;
    const Vec3 b = (v[t[1]] - reference) * invScale;
    const Vec3 c = (v[t[2]] - reference) * invScale;
    // Edge vectors rather than b x c: the rounding error is then a few ulps of |a| |n|, small
    // for a small triangle far from the reference, instead of |a| |b| |c|.
    const Vec3 n = (b - a).cross(c - a);
    const Vec3 sum = a + b + c;
    // Both models share Q = a a^T + b b^T + c c^T + sum sum^T: the tetrahedron (0, a, b, c) has
    // integral x x^T dV = det / 120 * Q and the triangle (a, b, c) has
    // integral x x^T dA = area / 12 * Q (canonical-element covariance mapped affinely).
    const Mat3 q = a * a.transpose() + b * b.transpose() + c * c.transpose() +
                   sum * sum.transpose();
    const double det = a.dot(n);
    s.det += det;
    s.detFirst += det * sum;
    s.detSecond += det * q;
    // Degenerate triangles are left out of the area (mesh.h: "zero area"), so `area` agrees
    // with the mesh's own notion; their true area is below 1e-12 of their longest edge squared.
    if (mesh.isDegenerate(i)) continue;
    const double w = n.norm();
    s.w += w;
    s.wFirst += w * sum;
    s.wSecond += w * q;
  }
  return s;
}

// Unit-mass properties from mass M, first moment F and second moment S (all in scaled
// coordinates about the reference), then mapped back to mesh units. mass > 0 is required.
MassProperties fromMoments(MassModel model, double mass, const Vec3& first, const Mat3& second,
                           const Vec3& reference, double scale) {
  MassProperties p;
  p.model = model;
  const Vec3 d = first / mass;  // centre of mass, scaled, relative to the reference
  // Parallel-axis shift to the centre of mass on the covariance, where it is a plain subtraction.
  Mat3 cov = second / mass - d * d.transpose();
  // Exact rounding gives a symmetric matrix already; symmetrising makes it a contract.
  cov = 0.5 * (cov + cov.transpose()).eval();
  const Mat3 inertiaScaled = cov.trace() * Mat3::Identity() - cov;
  p.centerOfMass = reference + d * scale;
  p.inertia = inertiaScaled * (scale * scale);
  return p;
}

void setPrincipalFrame(MassProperties& p) {
  // Eigen's iterative solver (not computeDirect): accurate also for nearly equal moments.
  const Eigen::SelfAdjointEigenSolver<Mat3> solver(p.inertia);
  if (solver.info() != Eigen::Success) {
    // Not seen for finite symmetric 3x3 input; kept so the result is defined regardless.
    p.principalAxes = Mat3::Identity();
    Vec3 m = p.inertia.diagonal().cwiseMax(0.0);
    std::sort(m.data(), m.data() + 3);
    p.principalMoments = m;
    return;
  }
  p.principalAxes = solver.eigenvectors();
  // Eigenvectors come with arbitrary signs; flipping one column turns a reflection into a
  // rotation without changing the diagonalisation.
  if (p.principalAxes.determinant() < 0.0) p.principalAxes.col(2) *= -1.0;
  // Eigenvalues come ascending; a true inertia tensor is positive semi-definite, so anything
  // below zero is rounding (e.g. the zero moment of a line-like body).
  p.principalMoments = solver.eigenvalues().cwiseMax(0.0);
}

bool allFinite(const MassProperties& p) {
  return std::isfinite(p.volume) && std::isfinite(p.area) && p.centerOfMass.allFinite() &&
         p.inertia.allFinite() && p.principalAxes.allFinite() && p.principalMoments.allFinite();
}

MassProperties pointMass(const Vec3& centre, bool closed) {
  MassProperties p;
  p.model = MassModel::ThinShell;
  p.centerOfMass = centre;
  p.closed = closed;
  return p;
}

}  // namespace

MassProperties computeMassProperties(const TriangleMesh& mesh) {
  const Aabb& bounds = mesh.bounds();
  // Halves first: 0.5 * (lo + hi) could overflow for coordinates near the double limit.
  const Vec3 reference = 0.5 * bounds.lo + 0.5 * bounds.hi;
  const Vec3 half = 0.5 * bounds.hi - 0.5 * bounds.lo;
  const bool closed = isClosed(mesh);
  if (mesh.report().degenerateTriangles == mesh.triangleCount()) {
    return pointMass(reference, closed);
  }

  int exponent = 0;
  std::frexp(half.maxCoeff(), &exponent);  // half.maxCoeff() < 2^exponent
  exponent = std::clamp(exponent, -kMaxScaleExponent, kMaxScaleExponent);
  const double scale = std::ldexp(1.0, exponent);
  const double invScale = std::ldexp(1.0, -exponent);
  const Sums s = accumulate(mesh, reference, invScale);

  const double scale2 = scale * scale;
  const double areaScaled = 0.5 * s.w;
  const double diagonalScaled = 2.0 * (half * invScale).norm();
  const double volumeScaled = s.det / 6.0;

  if (closed && std::abs(volumeScaled) > kFlatVolumeFraction * areaScaled * diagonalScaled) {
    // An inward-wound surface gives every tetrahedron the opposite sign: flipping the sign of
    // all solid sums recovers the outward result exactly.
    const double sign = volumeScaled < 0.0 ? -1.0 : 1.0;
    MassProperties p =
        fromMoments(MassModel::SolidVolume, sign * volumeScaled, sign * s.detFirst / 24.0,
                    sign * s.detSecond / 120.0, reference, scale);
    p.volume = sign * volumeScaled * scale2 * scale;
    p.area = areaScaled * scale2;
    p.closed = closed;
    setPrincipalFrame(p);
    // Only overflow/underflow of the rescaled numbers (sizes beyond ~1e100 or below ~1e-100)
    // can fail this; the shell model, with lower powers of the scale, is tried next.
    if (allFinite(p) && p.volume > 0.0) return p;
  }

  // areaScaled > 0: at least one triangle is not degenerate, and a non-degenerate triangle has
  // |n| > 1e-12 * longest edge^2 > 0 (the tolerance of TriangleMesh::isDegenerate).
  // The check still guards the division should the scaled area underflow.
  if (areaScaled > 0.0) {
    MassProperties p = fromMoments(MassModel::ThinShell, areaScaled, s.wFirst / 6.0,
                                   s.wSecond / 24.0, reference, scale);
    p.area = areaScaled * scale2;
    p.closed = closed;
    setPrincipalFrame(p);
    if (allFinite(p) && p.area > 0.0) return p;
  }
  return pointMass(reference, closed);
}

}  // namespace adb
