// The generators' shared parts: parameter checks, and the box and cylinder parts.
#include "generator_kit.h"

#include <cmath>
#include <sstream>
#include <unordered_map>

namespace adb::gen::kit {

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
// Torus knot

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

}  // namespace adb::gen::kit
