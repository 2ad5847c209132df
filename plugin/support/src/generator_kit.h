// Internal: what the shape generators share: parameter checks that name the generator,
// the Builder that grows a mesh, the lattice that most closed shapes are made of, and the
// box and cylinder parts that several shapes are built from.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "adb/core/mesh.h"

namespace adb::gen::kit {

inline constexpr double kPi = 3.14159265358979323846;
// TriangleMesh refuses more triangles than the tree can index (see mesh.cpp).
inline constexpr double kMaxTriangles = 268435455.0;

// Parameter checks: each throws MeshError naming the generator.
void require(bool ok, const char* function, const std::string& what);
std::string got(double value);
void requirePositive(const char* function, const char* name, double value);
void requireAtLeast(const char* function, const char* name, int value, int minimum);
// Refuses counts the mesh could not hold before allocating for them.
void requireCount(const char* function, double triangles);

class Builder {
 public:
  std::uint32_t vertex(const Vec3& p) {
    m_vertices.push_back(p);
    return static_cast<std::uint32_t>(m_vertices.size() - 1);
  }
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    m_triangles.push_back({a, b, c});
  }
  /// Quad a-b-c-d, counter-clockwise seen from outside; split along a-c.
  void quad(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t d) {
    triangle(a, b, c);
    triangle(a, c, d);
  }
  std::uint32_t vertexCount() const { return static_cast<std::uint32_t>(m_vertices.size()); }

  /// Appends `part` with its vertices mapped by `pose`.
  void append(const Builder& part, const Pose& pose) {
    const std::uint32_t base = vertexCount();
    for (const Vec3& v : part.m_vertices) {
      m_vertices.push_back(pose.apply(v));
    }
    for (const Triangle& t : part.m_triangles) triangle(base + t[0], base + t[1], base + t[2]);
  }

  TriangleMesh finish(const std::string& name) {
    return TriangleMesh(std::move(m_vertices), std::move(m_triangles), name);
  }

 private:
  std::vector<Vec3> m_vertices;
  std::vector<Triangle> m_triangles;
};

// Adds a rows x cols lattice of vertices pos(i, j) and one quad per cell, wound
// (i,j) -> (i+1,j) -> (i+1,j+1) -> (i,j+1): outward where d pos/di x d pos/dj points outward.
// A wrapped direction joins its last line to its first without duplicating seam vertices, so
// wrapping both directions gives a surface that is closed by index.
template <class PosFn>
void addGrid(Builder& b, int rows, int cols, bool wrapRows, bool wrapCols, PosFn&& pos) {
  const std::uint32_t base = b.vertexCount();
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < cols; ++j) b.vertex(pos(i, j));
  }
  const auto id = [&](int i, int j) {
    return base + static_cast<std::uint32_t>((i % rows) * cols + (j % cols));
  };
  const int cellRows = wrapRows ? rows : rows - 1;
  const int cellCols = wrapCols ? cols : cols - 1;
  for (int i = 0; i < cellRows; ++i) {
    for (int j = 0; j < cellCols; ++j) {
      b.quad(id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
    }
  }
}

inline double fraction(int i, int n) { return static_cast<double>(i) / static_cast<double>(n); }
inline double angle(int i, int n) { return 2.0 * kPi * fraction(i, n); }

// Rotation by `radians` about z.
inline Mat3 rotationZ(double radians) {
  return Eigen::AngleAxisd(radians, Vec3::UnitZ()).toRotationMatrix();
}


// A ring frame on a swept curve: ring points are origin + rho (cos a * n + sin a * b). With
// b = n x tangent, lattice rows along the curve and columns around the ring wind outward.
struct Frame {
  Vec3 origin, n, b;
  Vec3 ring(double rho, double a) const {
    return origin + rho * (std::cos(a) * n + std::sin(a) * b);
  }
};

// The torus knot's frame at parameter t (its centre line's point and ring axes), and the
// length of its centre line.
Frame torusKnotFrame(int p, int q, double radius, double t);
double torusKnotLength(int p, int q, double radius);

// Box surface with div[a] cells along axis a, closed by index.
Builder boxPart(const Vec3& half, const std::array<int, 3>& div);
// Solid cylinder along z, centred, closed by a fan at each cap centre.
Builder cylinderPart(double radius, double height, int segments, int heightSegments, int capRings);
// The triangle count makeLockAssembly(resolution) produces, without building it.
double lockTriangleCount(int resolution);

}  // namespace adb::gen::kit
