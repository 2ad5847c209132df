// Generated test geometry (adb::gen): the shape generators, merge/transform helpers and the
// named benchmark models. Most closed shapes are one wrapped quad lattice (torus topology):
// torus, knot tube, gear (a rectangle profile revolved) and pipe (an annulus profile swept).
#include "adb/support/mesh_generators.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <sstream>
#include <unordered_map>
#include <utility>

namespace adb::gen {
namespace {

constexpr double kPi = 3.14159265358979323846;
// TriangleMesh refuses more triangles than the tree can index (see mesh.cpp).
constexpr double kMaxTriangles = 268435455.0;

// ---------------------------------------------------------------------------------------------
// Parameter checks

void require(bool ok, const char* function, const std::string& what) {
  if (!ok) throw MeshError(std::string(function) + ": " + what);
}

std::string got(double value) {
  std::ostringstream os;
  os << " (got " << value << ")";
  return os.str();
}

void requirePositive(const char* function, const char* name, double value) {
  require(std::isfinite(value) && value > 0.0, function,
          std::string(name) + " must be > 0" + got(value));
}

void requireAtLeast(const char* function, const char* name, int value, int minimum) {
  require(value >= minimum, function,
          std::string(name) + " must be >= " + std::to_string(minimum) + got(value));
}

// Refuses counts the mesh could not hold before allocating for them.
void requireCount(const char* function, double triangles) {
  if (triangles <= kMaxTriangles) return;
  std::ostringstream os;
  os << function << ": the parameters ask for " << triangles
     << " triangles, more than a mesh can hold";
  throw MeshError(os.str());
}

// ---------------------------------------------------------------------------------------------
// Builder: growing vertex/triangle arrays, turned into a validated TriangleMesh at the end.

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

double fraction(int i, int n) { return static_cast<double>(i) / static_cast<double>(n); }
double angle(int i, int n) { return 2.0 * kPi * fraction(i, n); }

// Rotation by `radians` about z.
Mat3 rotationZ(double radians) {
  return Eigen::AngleAxisd(radians, Vec3::UnitZ()).toRotationMatrix();
}

// ---------------------------------------------------------------------------------------------
// Box

// Box surface with div[a] cells along axis a. Vertices are keyed by their integer lattice
// coordinates, so faces share their edge vertices and the box is closed by index.
Builder boxPart(const Vec3& half, const std::array<int, 3>& div) {
  Builder b;
  std::unordered_map<std::uint64_t, std::uint32_t> ids;
  const auto at = [&](std::array<int, 3> l) {
    const std::uint64_t key =
        (static_cast<std::uint64_t>(l[0]) * static_cast<std::uint64_t>(div[1] + 1) +
         static_cast<std::uint64_t>(l[1])) *
            static_cast<std::uint64_t>(div[2] + 1) +
        static_cast<std::uint64_t>(l[2]);
    const auto found = ids.find(key);
    if (found != ids.end()) return found->second;
    Vec3 p;
    // -h + 2h * l / n is exact at both ends, so the faces lie exactly on +-h.
    for (int a = 0; a < 3; ++a) p[a] = -half[a] + 2.0 * half[a] * fraction(l[a], div[a]);
    return ids.emplace(key, b.vertex(p)).first->second;
  };
  for (int a = 0; a < 3; ++a) {
    for (int side = 0; side < 2; ++side) {
      // e_u x e_v = +e_a; swapping u and v on the low side turns the normal to -e_a.
      int u = (a + 1) % 3, v = (a + 2) % 3;
      if (side == 0) std::swap(u, v);
      const auto corner = [&](int i, int j) {
        std::array<int, 3> l{};
        l[a] = side == 0 ? 0 : div[a];
        l[u] = i;
        l[v] = j;
        return at(l);
      };
      for (int i = 0; i < div[u]; ++i) {
        for (int j = 0; j < div[v]; ++j) {
          b.quad(corner(i, j), corner(i + 1, j), corner(i + 1, j + 1), corner(i, j + 1));
        }
      }
    }
  }
  return b;
}

// ---------------------------------------------------------------------------------------------
// Cylinder

// Solid cylinder along z: a revolved open profile (bottom cap rings outward, side upward, top
// cap rings inward; counter-clockwise in the (rho, z) plane, hence outward) closed by a fan at
// each cap centre. Only the two centres lie on the axis: a profile point on the axis would be
// repeated once per segment and give degenerate triangles.
Builder cylinderPart(double radius, double height, int segments, int heightSegments, int capRings) {
  const int cols = 2 * capRings + heightSegments - 1;
  const auto profile = [&](int j) -> std::pair<double, double> {  // (rho, z)
    const double h2 = 0.5 * height;
    if (j < capRings) return {radius * fraction(j + 1, capRings), -h2};
    if (j < capRings + heightSegments) {
      return {radius, -h2 + height * fraction(j - capRings + 1, heightSegments)};
    }
    return {radius * fraction(cols - j, capRings), h2};
  };
  Builder b;
  addGrid(b, segments, cols, true, false, [&](int i, int j) {
    const auto [rho, z] = profile(j);
    const double t = angle(i, segments);
    return Vec3(rho * std::cos(t), rho * std::sin(t), z);
  });
  const std::uint32_t bottom = b.vertex(Vec3(0, 0, -0.5 * height));
  const std::uint32_t top = b.vertex(Vec3(0, 0, 0.5 * height));
  const auto ring = [&](int i, int j) {
    return static_cast<std::uint32_t>((i % segments) * cols + j);
  };
  for (int i = 0; i < segments; ++i) {
    b.triangle(bottom, ring(i + 1, 0), ring(i, 0));  // seen from below: counter-clockwise
    b.triangle(top, ring(i, cols - 1), ring(i + 1, cols - 1));
  }
  return b;
}

// ---------------------------------------------------------------------------------------------
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

// ---------------------------------------------------------------------------------------------
// Torus knot

// A ring frame on a swept curve: ring points are origin + rho (cos a * n + sin a * b). With
// b = n x tangent, lattice rows along the curve and columns around the ring wind outward.
struct Frame {
  Vec3 origin, n, b;
  Vec3 ring(double rho, double a) const {
    return origin + rho * (std::cos(a) * n + std::sin(a) * b);
  }
};

// The knot lies on a torus (R, R/2); its offset from the torus core circle is normal to that
// torus and hence perpendicular to the tangent: a smooth, periodic frame (a Frenet or
// parallel-transport frame would twist or fail to close).
Frame torusKnotFrame(int p, int q, double radius, double t) {
  const double a = 0.5 * radius, pt = p * t, qt = q * t;
  const Vec3 n(std::cos(qt) * std::cos(pt), std::cos(qt) * std::sin(pt), std::sin(qt));
  const double rho = radius + a * std::cos(qt);
  const Vec3 tangent(-a * q * std::sin(qt) * std::cos(pt) - rho * p * std::sin(pt),
                     -a * q * std::sin(qt) * std::sin(pt) + rho * p * std::cos(pt),
                     a * q * std::cos(qt));
  const Vec3 origin = Vec3(radius * std::cos(pt), radius * std::sin(pt), 0.0) + a * n;
  return Frame{origin, n, n.cross(tangent).normalized()};
}

// Centre-line length, for choosing ring counts with square-ish quads.
double torusKnotLength(int p, int q, double radius) {
  constexpr int kSamples = 2048;
  double length = 0.0;
  Vec3 previous = torusKnotFrame(p, q, radius, 0.0).origin;
  for (int i = 1; i <= kSamples; ++i) {
    const Vec3 next = torusKnotFrame(p, q, radius, angle(i, kSamples)).origin;
    length += (next - previous).norm();
    previous = next;
  }
  return length;
}

// ---------------------------------------------------------------------------------------------
// Gear

// Tooth outline in fractions of the tooth pitch: rising flank, tip, falling flank, root land
// (which wraps into the next tooth). The tooth covers 55 % of the pitch at the root and 25 % at
// the tip, leaving room for a mating tooth.
struct ToothPiece {
  double start, end;
  bool startsAtTip, endsAtTip;
};
constexpr std::array<ToothPiece, 4> kToothPieces = {{
    {0.225, 0.375, false, true},
    {0.375, 0.625, true, true},
    {0.625, 0.775, true, false},
    {0.775, 1.225, false, false},
}};

// Samples per piece: at least one each, the rest roughly in proportion to the piece's length.
std::array<int, 4> toothPieceSamples(int segmentsPerTooth) {
  const int flank = std::max(1, static_cast<int>(std::lround(0.15 * segmentsPerTooth)));
  const int tip = std::max(1, static_cast<int>(std::lround(0.25 * segmentsPerTooth)));
  return {flank, tip, flank, segmentsPerTooth - 2 * flank - tip};
}

// (angle, outer radius) of every outline sample, counter-clockwise from the first flank.
std::vector<std::pair<double, double>> gearOutline(int teeth, double outerRadius, double rootRadius,
                                                   int segmentsPerTooth) {
  const std::array<int, 4> samples = toothPieceSamples(segmentsPerTooth);
  std::vector<std::pair<double, double>> outline;
  outline.reserve(static_cast<std::size_t>(teeth * segmentsPerTooth));
  for (int tooth = 0; tooth < teeth; ++tooth) {
    for (std::size_t k = 0; k < kToothPieces.size(); ++k) {
      const ToothPiece& piece = kToothPieces[k];
      const double r0 = piece.startsAtTip ? outerRadius : rootRadius;
      const double r1 = piece.endsAtTip ? outerRadius : rootRadius;
      for (int s = 0; s < samples[k]; ++s) {
        const double f = fraction(s, samples[k]);
        const double phase = piece.start + f * (piece.end - piece.start);
        outline.emplace_back(2.0 * kPi * (tooth + phase) / teeth, r0 + f * (r1 - r0));
      }
    }
  }
  return outline;
}

struct GearShape {
  int teeth;
  double outerRadius, rootRadius, boreRadius, thickness;
  int segmentsPerTooth, radialSegments, axialSegments;
};

void checkGear(const char* fn, const GearShape& g) {
  requireAtLeast(fn, "teeth", g.teeth, 3);
  requirePositive(fn, "boreRadius", g.boreRadius);
  requirePositive(fn, "thickness", g.thickness);
  require(g.boreRadius < g.rootRadius && g.rootRadius < g.outerRadius, fn,
          "need 0 < boreRadius < rootRadius < outerRadius");
  requireAtLeast(fn, "segmentsPerTooth", g.segmentsPerTooth, 4);
  requireAtLeast(fn, "radialSegments", g.radialSegments, 1);
  requireAtLeast(fn, "axialSegments", g.axialSegments, 1);
  requireCount(fn, 4.0 * g.teeth * g.segmentsPerTooth *
                       (static_cast<double>(g.radialSegments) + g.axialSegments));
}

// The gear is a revolved closed profile: bottom face outward, outer wall up, top face inward,
// bore wall down; counter-clockwise in the (rho, z) plane, so the lattice winds outward.
Builder gearPart(const GearShape& g) {
  const auto outline = gearOutline(g.teeth, g.outerRadius, g.rootRadius, g.segmentsPerTooth);
  const int dr = g.radialSegments, dz = g.axialSegments;
  const double h2 = 0.5 * g.thickness;
  const auto profile = [&](double outer, int j) -> std::pair<double, double> {  // (rho, z)
    const double span = outer - g.boreRadius;
    if (j < dr) return {g.boreRadius + span * fraction(j, dr), -h2};
    if (j < dr + dz) return {outer, -h2 + g.thickness * fraction(j - dr, dz)};
    if (j < 2 * dr + dz) return {outer - span * fraction(j - dr - dz, dr), h2};
    return {g.boreRadius, h2 - g.thickness * fraction(j - 2 * dr - dz, dz)};
  };
  Builder b;
  addGrid(b, static_cast<int>(outline.size()), 2 * (dr + dz), true, true, [&](int i, int j) {
    const auto [theta, outer] = outline[static_cast<std::size_t>(i)];
    const auto [rho, z] = profile(outer, j);
    return Vec3(rho * std::cos(theta), rho * std::sin(theta), z);
  });
  return b;
}

// ---------------------------------------------------------------------------------------------
// Pipe bundle

constexpr double kPipeBend = 0.5 * kPi;  // each pipe bends by 90 degrees

// One pipe along a horizontal 90-degree arc, its bend centred on x = 0. Lattice rows go around
// the pipe, columns along a closed annulus profile: outer wall from the far end back to the
// start, start cap inwards, inner wall forwards, far-end cap outwards. Rows and columns are
// swapped relative to the knot tube, which flips the winding; running the outer wall backwards
// flips it back, so the lattice winds outward (and the inner wall faces the pipe's axis).
Builder pipePart(double length, double radius, double wall, int segments, int lengthSegments) {
  const double bend = length / kPipeBend;
  const double centreX = -0.5 * bend * (1.0 + std::cos(0.5 * kPipeBend));
  const int ring = lengthSegments + 1;
  const auto frameAt = [&](int k) {
    const double phi = -0.5 * kPipeBend + kPipeBend * fraction(k, lengthSegments);
    const Vec3 n(std::cos(phi), std::sin(phi), 0.0), tangent(-std::sin(phi), std::cos(phi), 0.0);
    return Frame{Vec3(centreX, 0, 0) + bend * n, n, n.cross(tangent)};
  };
  Builder b;
  addGrid(b, segments, 2 * ring, true, true, [&](int i, int j) {
    const bool outer = j < ring;
    const int k = outer ? lengthSegments - j : j - ring;
    return frameAt(k).ring(outer ? radius : radius - wall, angle(i, segments));
  });
  return b;
}

// ---------------------------------------------------------------------------------------------
// Lock assembly

struct LockBox {
  Vec3 centre, half;
};
struct LockCylinder {
  Vec3 centre, axis;
  double radius, height;
};

// Housing plate and bolt; the bolt runs through the plate's right edge.
const std::array<LockBox, 2> kLockBoxes = {{
    {Vec3(0.0, 0.0, 0.0), Vec3(0.75, 0.5, 0.1)},
    {Vec3(0.6, -0.05, 0.0), Vec3(0.4, 0.1, 0.06)},
}};

// Plug through the plate, three pins above it, two screws (one along y, so that a rotated
// part is part of the model).
const std::array<LockCylinder, 6> kLockCylinders = {{
    {Vec3(-0.3, 0.0, 0.0), Vec3::UnitZ(), 0.22, 0.36},
    {Vec3(-0.42, 0.32, 0.0), Vec3::UnitZ(), 0.04, 0.3},
    {Vec3(-0.30, 0.32, 0.0), Vec3::UnitZ(), 0.04, 0.3},
    {Vec3(-0.18, 0.32, 0.0), Vec3::UnitZ(), 0.04, 0.3},
    {Vec3(0.6, 0.38, 0.0), Vec3::UnitZ(), 0.05, 0.26},
    {Vec3(0.6, -0.38, 0.0), Vec3::UnitY(), 0.05, 0.26},
}};

int cellsFor(double length, double edge, int minimum) {
  return std::max(minimum, static_cast<int>(std::lround(length / edge)));
}

std::array<int, 3> lockBoxCells(const LockBox& box, double edge) {
  return {cellsFor(2 * box.half.x(), edge, 1), cellsFor(2 * box.half.y(), edge, 1),
          cellsFor(2 * box.half.z(), edge, 1)};
}

// (segments, heightSegments, capRings) for a lock cylinder.
std::array<int, 3> lockCylinderCells(const LockCylinder& c, double edge) {
  return {cellsFor(2 * kPi * c.radius, edge, 8), cellsFor(c.height, edge, 1),
          cellsFor(c.radius, edge, 1)};
}

// The same count makeLockAssembly(resolution) produces, without building it.
double lockTriangleCount(int resolution) {
  const double edge = 1.0 / resolution;
  double count = 0.0;
  for (const LockBox& box : kLockBoxes) {
    const auto n = lockBoxCells(box, edge);
    count += 4.0 * (n[0] * n[1] + n[1] * n[2] + n[2] * n[0]);
  }
  for (const LockCylinder& c : kLockCylinders) {
    const auto n = lockCylinderCells(c, edge);
    count += 2.0 * n[0] * (n[1] + 2 * n[2] - 1);
  }
  return count;
}

// ---------------------------------------------------------------------------------------------
// Named models: each picks its parameters from the target count (closed form where a free
// parameter can absorb the rounding, a scan over resolutions for the lock).

int roundedAtLeast(double value, int minimum) {
  return std::max(minimum, static_cast<int>(std::lround(value)));
}

TriangleMesh sphereModel(double target) {
  return makeSphere(0.8, roundedAtLeast(std::sqrt(target / 20.0), 2));
}

TriangleMesh torusModel(double target) {
  // 3 major per minor segment keeps the quads near square for radii 0.6 / 0.25.
  const int minor = roundedAtLeast(std::sqrt(target / 6.0), 3);
  return makeTorus(0.6, 0.25, roundedAtLeast(target / (2.0 * minor), 3), minor);
}

TriangleMesh knotModel(double target) {
  constexpr double kRadius = 0.55, kTube = 0.09;
  const double aspect = torusKnotLength(2, 3, kRadius) / (2.0 * kPi * kTube);
  const int around = roundedAtLeast(std::sqrt(target / (2.0 * aspect)), 6);
  return makeTorusKnot(2, 3, kRadius, kTube, roundedAtLeast(target / (2.0 * around), 12), around);
}

TriangleMesh gearsModel(double target) {
  // Pair of 12-tooth gears: 192 * segmentsPerTooth * layers triangles. Flooring the layer count
  // keeps segmentsPerTooth >= 4 * layers, so its rounding costs at most 12.5 %.
  const int layers = std::max(1, static_cast<int>(std::sqrt(target / 768.0)));
  const int perTooth = roundedAtLeast(target / (192.0 * layers), 4);
  return makeGearPair(12, 0.5, 0.4, 0.15, 0.25, perTooth, layers, layers);
}

TriangleMesh pipesModel(double target) {
  constexpr int kPipes = 6;
  constexpr double kLength = 1.6, kRadius = 0.08;
  const double aspect = kLength / (2.0 * kPi * kRadius);
  const int around = roundedAtLeast(std::sqrt(target / (4.0 * kPipes * aspect)), 8);
  const int rings = roundedAtLeast(target / (4.0 * kPipes * around), 2);
  return makePipeBundle(kPipes, kLength, kRadius, 0.02, around, rings - 1);
}

TriangleMesh lockModel(double target) {
  int best = 1;
  for (int r = 1; r < 4096; ++r) {
    const double count = lockTriangleCount(r);
    if (std::abs(std::log(count / target)) < std::abs(std::log(lockTriangleCount(best) / target))) {
      best = r;
    }
    if (count > 2.0 * target) break;
  }
  return makeLockAssembly(best);
}

struct NamedModel {
  const char* name;
  TriangleMesh (*make)(double target);
};

constexpr std::array<NamedModel, 6> kModels = {{
    {"pipes", pipesModel},
    {"gears", gearsModel},
    {"lock", lockModel},
    {"knot", knotModel},
    {"torus", torusModel},
    {"sphere", sphereModel},
}};

// TriangleMesh has no setter for its name; a model is renamed by copying (once per makeModel).
TriangleMesh named(const TriangleMesh& mesh, const std::string& name) {
  return TriangleMesh(mesh.vertices(), mesh.triangles(), name);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// Public generators

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

TriangleMesh makeTorus(double majorRadius, double minorRadius, int majorSegments,
                       int minorSegments) {
  const char* fn = "makeTorus";
  requirePositive(fn, "minorRadius", minorRadius);
  require(majorRadius > minorRadius, fn, "majorRadius must exceed minorRadius" + got(majorRadius));
  requireAtLeast(fn, "majorSegments", majorSegments, 3);
  requireAtLeast(fn, "minorSegments", minorSegments, 3);
  requireCount(fn, 2.0 * majorSegments * static_cast<double>(minorSegments));
  Builder b;
  // Rows around z, columns around the tube: d/du x d/dv is the outward tube normal.
  addGrid(b, majorSegments, minorSegments, true, true, [&](int i, int j) {
    const double u = angle(i, majorSegments), v = angle(j, minorSegments);
    const double rho = majorRadius + minorRadius * std::cos(v);
    return Vec3(rho * std::cos(u), rho * std::sin(u), minorRadius * std::sin(v));
  });
  return b.finish("torus");
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

TriangleMesh makeTorusKnot(int p, int q, double radius, double tubeRadius, int segments,
                           int tubeSegments) {
  const char* fn = "makeTorusKnot";
  requireAtLeast(fn, "p", p, 1);
  requireAtLeast(fn, "q", q, 1);
  require(std::gcd(p, q) == 1, fn,
          "p and q must be coprime (got " + std::to_string(p) + ", " + std::to_string(q) + ")");
  requirePositive(fn, "radius", radius);
  requirePositive(fn, "tubeRadius", tubeRadius);
  require(tubeRadius < 0.5 * radius, fn, "tubeRadius must be below radius / 2" + got(tubeRadius));
  requireAtLeast(fn, "segments", segments, 3);
  requireAtLeast(fn, "tubeSegments", tubeSegments, 3);
  requireCount(fn, 2.0 * segments * static_cast<double>(tubeSegments));
  Builder b;
  addGrid(b, segments, tubeSegments, true, true, [&](int i, int j) {
    return torusKnotFrame(p, q, radius, angle(i, segments))
        .ring(tubeRadius, angle(j, tubeSegments));
  });
  return b.finish("torus_knot");
}

TriangleMesh makeGear(int teeth, double outerRadius, double rootRadius, double boreRadius,
                      double thickness, int segmentsPerTooth, int radialSegments,
                      int axialSegments) {
  const GearShape g{teeth,     outerRadius,      rootRadius,     boreRadius,
                    thickness, segmentsPerTooth, radialSegments, axialSegments};
  checkGear("makeGear", g);
  return gearPart(g).finish("gear");
}

TriangleMesh makeGearPair(int teeth, double outerRadius, double rootRadius, double boreRadius,
                          double thickness, int segmentsPerTooth, int radialSegments,
                          int axialSegments) {
  const GearShape g{teeth,     outerRadius,      rootRadius,     boreRadius,
                    thickness, segmentsPerTooth, radialSegments, axialSegments};
  checkGear("makeGearPair", g);
  const Builder gear = gearPart(g);
  // Teeth are centred at pi/teeth + k * pitch. Turning the left gear by -pi/teeth puts a tooth
  // on +x; turning the right one by pi puts a gap (the middle of a root land) on -x.
  const double distance = outerRadius + rootRadius + 0.3 * (outerRadius - rootRadius);
  Builder b;
  b.append(gear, Pose{rotationZ(-kPi / teeth), Vec3(-0.5 * distance, 0, 0)});
  b.append(gear, Pose{rotationZ(kPi), Vec3(0.5 * distance, 0, 0)});
  return b.finish("gear_pair");
}

TriangleMesh makePipeBundle(int pipes, double length, double radius, double wallThickness,
                            int segments, int lengthSegments) {
  const char* fn = "makePipeBundle";
  requireAtLeast(fn, "pipes", pipes, 1);
  requirePositive(fn, "radius", radius);
  requirePositive(fn, "wallThickness", wallThickness);
  require(wallThickness < radius, fn, "wallThickness must be below radius" + got(wallThickness));
  // The bend radius (length / (pi/2)) must exceed the pipe radius or the wall folds over.
  require(length > kPipeBend * radius, fn, "length must exceed pi/2 * radius" + got(length));
  requireAtLeast(fn, "segments", segments, 3);
  requireAtLeast(fn, "lengthSegments", lengthSegments, 1);
  requireCount(fn, 4.0 * pipes * static_cast<double>(segments) * (lengthSegments + 1.0));
  const Builder pipe = pipePart(length, radius, wallThickness, segments, lengthSegments);
  const double layer = 2.5 * radius;  // pipe diameter plus a gap of half a radius
  Builder b;
  for (int k = 0; k < pipes; ++k) {
    const double z = (k - 0.5 * (pipes - 1)) * layer;
    b.append(pipe, Pose{rotationZ(kPi * k / pipes), Vec3(0, 0, z)});
  }
  return b.finish("pipe_bundle");
}

TriangleMesh makeLockAssembly(int resolution) {
  const char* fn = "makeLockAssembly";
  requireAtLeast(fn, "resolution", resolution, 1);
  requireCount(fn, lockTriangleCount(resolution));
  const double edge = 1.0 / resolution;
  Builder b;
  for (const LockBox& box : kLockBoxes) {
    b.append(boxPart(box.half, lockBoxCells(box, edge)), Pose{Mat3::Identity(), box.centre});
  }
  for (const LockCylinder& c : kLockCylinders) {
    const auto n = lockCylinderCells(c, edge);
    const Eigen::Quaterniond toAxis = Eigen::Quaterniond::FromTwoVectors(Vec3::UnitZ(), c.axis);
    b.append(cylinderPart(c.radius, c.height, n[0], n[1], n[2]),
             Pose::fromQuaternion(toAxis, c.centre));
  }
  return b.finish("lock_assembly");
}

std::vector<std::string> modelNames() {
  std::vector<std::string> names;
  for (const NamedModel& m : kModels) names.emplace_back(m.name);
  return names;
}

TriangleMesh makeModel(const std::string& name, std::size_t targetTriangles) {
  const double target = std::max(1.0, static_cast<double>(targetTriangles));
  for (const NamedModel& m : kModels) {
    if (name == m.name) return named(m.make(target), name);
  }
  std::string known;
  for (const NamedModel& m : kModels) known += (known.empty() ? "" : ", ") + std::string(m.name);
  throw MeshError("makeModel: unknown model name \"" + name + "\"; known models: " + known);
}

TriangleMesh merge(const std::vector<TriangleMesh>& meshes, const std::string& name) {
  require(!meshes.empty(), "merge", "no meshes to merge");
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;
  for (const TriangleMesh& mesh : meshes) {
    const auto base = static_cast<std::uint32_t>(vertices.size());
    vertices.insert(vertices.end(), mesh.vertices().begin(), mesh.vertices().end());
    for (const Triangle& t : mesh.triangles()) {
      triangles.push_back({base + t[0], base + t[1], base + t[2]});
    }
  }
  return TriangleMesh(std::move(vertices), std::move(triangles), name);
}

TriangleMesh transformed(const TriangleMesh& mesh, const Pose& pose) {
  std::vector<Vec3> vertices;
  vertices.reserve(mesh.vertices().size());
  for (const Vec3& v : mesh.vertices()) vertices.push_back(pose.apply(v));
  return TriangleMesh(std::move(vertices), mesh.triangles(), mesh.name());
}

}  // namespace adb::gen
