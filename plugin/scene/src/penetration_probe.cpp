// PenetrationProbe: the deepest vertex of one body inside another, from the geometry alone.
#include "adb/scene/penetration_probe.h"

#include <algorithm>
#include <cmath>

#include "adb/core/box_query.h"
#include "adb/core/primitive_contact.h"
#include "adb/core/ray_query.h"

namespace adb::scene {
namespace {

// Three skewed directions, far from the axes and from each other: a mesh built on a grid
// rarely has an edge or a face exactly along one of them.
const Vec3 kRays[3] = {Vec3(0.5377, 0.8311, 0.1398).normalized(),
                       Vec3(-0.7213, 0.1874, 0.6667).normalized(),
                       Vec3(0.2611, -0.5183, 0.8144).normalized()};

// Whether the segment from -> from + d (d not normalised) crosses triangle (a, b, c), at a
// fraction in (0, 1] (Moller-Trumbore).
bool segmentCrosses(const Vec3& from, const Vec3& d, const Vec3& a, const Vec3& b,
                    const Vec3& c) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = d.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-300) return false;  // parallel: no crossing
  const double inv = 1.0 / det;
  const Vec3 s = from - a;
  const double u = s.dot(p) * inv;
  if (u < 0.0 || u > 1.0) return false;
  const Vec3 q = s.cross(e1);
  const double v = d.dot(q) * inv;
  if (v < 0.0 || u + v > 1.0) return false;
  const double t = e2.dot(q) * inv;
  return t > 0.0 && t <= 1.0;
}

int crossings(const AdbTree& tree, const Vec3& point, const Vec3& direction, double length) {
  SegmentQuery q;
  q.from = point + tree.origin();  // the query is in mesh coordinates
  q.to = q.from + direction * length;
  const Vec3 d = direction * length;
  const auto& vertices = tree.localVertices();
  int count = 0;
  forEachTriangleAlongSegment(tree, q, 1.0, [&](std::uint32_t t) {
    const Triangle& tri = tree.triangles()[t];
    if (segmentCrosses(point, d, vertices[tri[0]], vertices[tri[1]], vertices[tri[2]])) ++count;
    return 1.0;  // every crossing counts
  });
  return count;
}

// The body's vertices in world coordinates, and their box.
Aabb toWorld(const ProbeBody& body, std::vector<Vec3>& world) {
  Aabb box;
  world.clear();
  world.reserve(body.vertices->size());
  for (const Vec3& v : *body.vertices) {
    world.push_back(body.pose.apply(v));
    box.grow(world.back());
  }
  return box;
}

Aabb intersection(const Aabb& x, const Aabb& y) {
  Aabb r;
  r.lo = x.lo.cwiseMax(y.lo);
  r.hi = x.hi.cwiseMin(y.hi);
  return r;
}

bool contains(const Aabb& box, const Vec3& p) {
  return (p.array() >= box.lo.array()).all() && (p.array() <= box.hi.array()).all();
}

// A body's size: its mesh's bounding-box diagonal, whatever its orientation.
double sizeOf(const AdbTree& tree) { return (tree.root().boxHi() - tree.root().boxLo()).norm(); }

}  // namespace

bool insideMesh(const AdbTree& tree, const Vec3& point) {
  const Vec3 lo = tree.root().boxLo(), hi = tree.root().boxHi();
  if ((point.array() < lo.array()).any() || (point.array() > hi.array()).any()) return false;
  // Long enough to leave the root's box from anywhere inside it.
  const double length = 2.0 * (hi - lo).norm() + 1e-9;
  int odd = 0;
  for (const Vec3& r : kRays) odd += crossings(tree, point, r, length) % 2;
  return odd >= 2;
}

double distanceToMesh(const AdbTree& tree, const Vec3& point) {
  const double diagonal = (tree.root().boxHi() - tree.root().boxLo()).norm();
  const auto& vertices = tree.localVertices();
  // Grow a box around the point until the nearest triangle found lies within it: then no
  // triangle outside the box can be nearer.
  for (double r = std::max(1e-6, diagonal / 64.0);; r *= 2.0) {
    double best = std::numeric_limits<double>::infinity();
    Aabb box;
    box.lo = point + tree.origin() - Vec3::Constant(r);
    box.hi = point + tree.origin() + Vec3::Constant(r);
    forEachTriangleNear(tree, box, [&](std::uint32_t t) {
      const Triangle& tri = tree.triangles()[t];
      const Vec3 c = closestPointOnTriangle(point, vertices[tri[0]], vertices[tri[1]],
                                            vertices[tri[2]]);
      best = std::min(best, (c - point).norm());
    });
    if (best <= r || r > 4.0 * diagonal) return best;
  }
}

double deepestVertexInside(const ProbeBody& a, const std::vector<Vec3>& worldVertices,
                           const Aabb& region) {
  double deepest = 0.0;
  const Mat3 toA = a.pose.rotation.transpose();
  for (const Vec3& world : worldVertices) {
    if (!contains(region, world)) continue;
    const Vec3 local = toA * (world - a.pose.translation) - a.tree->origin();
    if (!insideMesh(*a.tree, local)) continue;
    deepest = std::max(deepest, distanceToMesh(*a.tree, local));
  }
  return deepest;
}

PenetrationReport measurePenetration(const std::vector<ProbeBody>& bodies) {
  PenetrationReport report;
  // Each body's vertices are placed in the world once, not once per pair it is in.
  std::vector<std::vector<Vec3>> world(bodies.size());
  std::vector<Aabb> boxes;
  boxes.reserve(bodies.size());
  for (std::size_t i = 0; i < bodies.size(); ++i) boxes.push_back(toWorld(bodies[i], world[i]));
  std::vector<double> deepest(bodies.size(), 0.0);
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    for (std::size_t j = i + 1; j < bodies.size(); ++j) {
      const Aabb region = intersection(boxes[i], boxes[j]);
      if (region.empty()) continue;
      ++report.pairsTested;
      const double intoI = deepestVertexInside(bodies[i], world[j], region);
      const double intoJ = deepestVertexInside(bodies[j], world[i], region);
      const double sizeI = sizeOf(*bodies[i].tree), sizeJ = sizeOf(*bodies[j].tree);
      const double depth = std::max(intoI, intoJ);
      deepest[i] = std::max(deepest[i], depth);
      deepest[j] = std::max(deepest[j], depth);
      report.depth = std::max(report.depth, depth);
      if (sizeI > 0.0) report.relative = std::max(report.relative, intoI / sizeI);
      if (sizeJ > 0.0) report.relative = std::max(report.relative, intoJ / sizeJ);
    }
  }
  double sum = 0.0;
  for (double d : deepest) sum += d;
  report.meanDepth = bodies.empty() ? 0.0 : sum / static_cast<double>(bodies.size());
  return report;
}

}  // namespace adb::scene
