// Tubes around closed curves: the torus and the torus knot (one wrapped quad lattice each).
#include "adb/support/mesh_generators.h"

#include <cmath>
#include <numeric>
#include <string>

#include "generator_kit.h"

namespace adb::gen {
using namespace kit;  // the generators' shared parts

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

}  // namespace adb::gen
