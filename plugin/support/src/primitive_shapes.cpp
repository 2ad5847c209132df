// Primitive shapes: box, flat grid, icosphere, cylinder.
#include "adb/support/mesh_generators.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>

#include "generator_kit.h"

namespace adb::gen {
using namespace kit;  // the generators' shared parts
namespace {

// Icosphere

const std::array<Vec3, 12>& icosahedronVertices() {
  static const std::array<Vec3, 12> v = [] {
    const double t = (1.0 + std::sqrt(5.0)) / 2.0;
    std::array<Vec3, 12> p = {Vec3(-1, t, 0), Vec3(1, t, 0), Vec3(-1, -t, 0), Vec3(1, -t, 0),
                              Vec3(0, -1, t), Vec3(0, 1, t), Vec3(0, -1, -t), Vec3(0, 1, -t),
                              Vec3(t, 0, -1), Vec3(t, 0, 1), Vec3(-t, 0, -1), Vec3(-t, 0, 1)};
    for (Vec3& x : p) x.normalize();
    return p;
  }();
  return v;
}

// Counter-clockwise seen from outside.
constexpr std::array<std::array<int, 3>, 20> kIcosahedronFaces = {{
    {0, 11, 5},  {0, 5, 1},  {0, 1, 7},  {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
    {11, 10, 2}, {10, 7, 6}, {7, 1, 8},  {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
    {3, 8, 9},   {4, 9, 5},  {2, 4, 11}, {6, 2, 10}, {8, 6, 7},   {9, 8, 1},
}};

// Shares the vertices that lie on icosahedron edges or corners between the faces meeting there.
// Such a point is identified by its non-zero barycentric weights over global corner ids, which
// are the same whichever face computes them.
class IcosphereVertices {
 public:
  IcosphereVertices(Builder& b, int n, double radius) : m_b(b), m_n(n), m_radius(radius) {}

  std::uint32_t at(const std::array<int, 3>& corners, const std::array<int, 3>& weights) {
    const bool interior = weights[0] > 0 && weights[1] > 0 && weights[2] > 0;
    if (interior) return m_b.vertex(position(corners, weights));
    const std::uint64_t key = boundaryKey(corners, weights);
    const auto found = m_ids.find(key);
    if (found != m_ids.end()) return found->second;
    return m_ids.emplace(key, m_b.vertex(position(corners, weights))).first->second;
  }

 private:
  Vec3 position(const std::array<int, 3>& corners, const std::array<int, 3>& weights) const {
    Vec3 p = Vec3::Zero();
    for (int k = 0; k < 3; ++k) {
      p += static_cast<double>(weights[k]) * icosahedronVertices()[corners[k]];
    }
    return m_radius * p.normalized();
  }

  // At most two non-zero weights on the boundary; pack (corner, weight) pairs sorted by corner.
  std::uint64_t boundaryKey(const std::array<int, 3>& corners,
                            const std::array<int, 3>& weights) const {
    std::array<std::uint64_t, 3> codes{};
    for (int k = 0; k < 3; ++k) {
      codes[k] =
          weights[k] == 0 ? 0 : static_cast<std::uint64_t>(corners[k] * (m_n + 1) + weights[k]);
    }
    std::sort(codes.begin(), codes.end());
    return (codes[2] << 42) | (codes[1] << 21) | codes[0];
  }

  Builder& m_b;
  int m_n;
  double m_radius;
  std::unordered_map<std::uint64_t, std::uint32_t> m_ids;
};

// One icosahedron face split into n^2 triangles; lattice point (i, j) has weights
// (n - i - j, i, j) on the face corners (A, B, C), so "up" and "down" triangles keep ABC's
// winding.
void addIcosphereFace(IcosphereVertices& verts, Builder& b, const std::array<int, 3>& face, int n) {
  std::vector<std::uint32_t> ids(static_cast<std::size_t>((n + 1) * (n + 2) / 2));
  const auto slot = [n](int i, int j) {
    return static_cast<std::size_t>(i * (n + 1) - i * (i - 1) / 2 + j);
  };
  for (int i = 0; i <= n; ++i) {
    for (int j = 0; i + j <= n; ++j) ids[slot(i, j)] = verts.at(face, {n - i - j, i, j});
  }
  for (int i = 0; i < n; ++i) {
    for (int j = 0; i + j < n; ++j) {
      b.triangle(ids[slot(i, j)], ids[slot(i + 1, j)], ids[slot(i, j + 1)]);
      if (i + j < n - 1) {
        b.triangle(ids[slot(i + 1, j)], ids[slot(i + 1, j + 1)], ids[slot(i, j + 1)]);
      }
    }
  }
}

}  // namespace

TriangleMesh makeBox(const Vec3& halfExtents, int subdivisions) {
  const char* fn = "makeBox";
  for (int a = 0; a < 3; ++a) requirePositive(fn, "halfExtents", halfExtents[a]);
  requireAtLeast(fn, "subdivisions", subdivisions, 1);
  requireCount(fn, 12.0 * subdivisions * static_cast<double>(subdivisions));
  return boxPart(halfExtents, {subdivisions, subdivisions, subdivisions}).finish("box");
}

TriangleMesh makeFlatGrid(double sizeX, double sizeY, int nx, int ny) {
  const char* fn = "makeFlatGrid";
  requirePositive(fn, "sizeX", sizeX);
  requirePositive(fn, "sizeY", sizeY);
  requireAtLeast(fn, "nx", nx, 1);
  requireAtLeast(fn, "ny", ny, 1);
  requireCount(fn, 2.0 * nx * static_cast<double>(ny));
  Builder b;
  // Rows along +x, columns along +y: cells wind counter-clockwise seen from +z.
  addGrid(b, nx + 1, ny + 1, false, false, [&](int i, int j) {
    return Vec3(sizeX * (fraction(i, nx) - 0.5), sizeY * (fraction(j, ny) - 0.5), 0.0);
  });
  return b.finish("flat_grid");
}

TriangleMesh makeSphere(double radius, int subdivisions) {
  const char* fn = "makeSphere";
  requirePositive(fn, "radius", radius);
  requireAtLeast(fn, "subdivisions", subdivisions, 1);
  requireCount(fn, 20.0 * subdivisions * static_cast<double>(subdivisions));
  Builder b;
  IcosphereVertices verts(b, subdivisions, radius);
  for (const auto& face : kIcosahedronFaces) addIcosphereFace(verts, b, face, subdivisions);
  return b.finish("sphere");
}

TriangleMesh makeCylinder(double radius, double height, int segments, int heightSegments,
                          int capRings) {
  const char* fn = "makeCylinder";
  requirePositive(fn, "radius", radius);
  requirePositive(fn, "height", height);
  requireAtLeast(fn, "segments", segments, 3);
  requireAtLeast(fn, "heightSegments", heightSegments, 1);
  requireAtLeast(fn, "capRings", capRings, 1);
  requireCount(fn, 2.0 * segments * (static_cast<double>(heightSegments) + 2.0 * capRings));
  return cylinderPart(radius, height, segments, heightSegments, capRings).finish("cylinder");
}

}  // namespace adb::gen
