// Gears: a rectangle profile revolved with teeth, and a meshing pair.
#include "adb/support/mesh_generators.h"

#include <array>
#include <cmath>

#include "generator_kit.h"

namespace adb::gen {
using namespace kit;  // the generators' shared parts
namespace {

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

}  // namespace

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

}  // namespace adb::gen
