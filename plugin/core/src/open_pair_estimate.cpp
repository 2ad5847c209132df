// The open-pair estimate (adb/core/open_pair_estimate.h).
#include "adb/core/open_pair_estimate.h"

#include <algorithm>
#include <cmath>

#include "adb/core/collision_estimate.h"

namespace adb {
namespace {

// The pair's nodes hold few triangles or slivers (QuerySettings::minTrianglesToAccept's
// default): the cell model is blind to it, and its fill speaks instead.
constexpr int kModelTriangles = 64;

// Fitted by `build/bin/adb-calibrate` (docs/probability-model.md gives the run).
constexpr OpenPairWeights kOpenPairWeights{-6.0585, 0.2116, 0.94658, 0.483268, 0.314571, 2.6093};

double finiteOr(double x, double otherwise) { return std::isfinite(x) ? x : otherwise; }

}  // namespace

std::array<double, kOpenPairFeatures> openPairFeatures(const OpenPair& o, const AdbTree& a,
                                                       const AdbTree& b) {
  const NodeOccupancy& oa = a.occupancy()[o.a];
  const NodeOccupancy& ob = b.occupancy()[o.b];
  const bool blind = std::min<int>(oa.triangles, ob.triangles) < kModelTriangles || oa.slivers ||
                     ob.slivers;
  const double expected = std::clamp(finiteOr(o.expected, 0.0), 0.0, 1e30);
  return {1.0,
          std::log(expected + 1e-3),
          std::clamp(finiteOr(o.fill, 0.0), 0.0, 1.0),
          std::log(static_cast<double>(oa.triangles) + static_cast<double>(ob.triangles) + 1.0),
          blind ? 1.0 : 0.0,
          std::clamp(finiteOr(o.p, 0.0), 0.0, 1.0)};
}

double openPairProbability(const std::array<double, kOpenPairFeatures>& f,
                           const OpenPairWeights& w) {
  double z = 0.0;
  for (int i = 0; i < kOpenPairFeatures; ++i) z += w[i] * f[i];
  if (std::isnan(z)) return 0.5;
  const double p = z >= 0.0 ? 1.0 / (1.0 + std::exp(-z)) : std::exp(z) / (1.0 + std::exp(z));
  return std::clamp(p, 0.0, 1.0);
}

double openPairProbability(const OpenPair& o, const AdbTree& a, const AdbTree& b) {
  return openPairProbability(openPairFeatures(o, a, b), kOpenPairWeights);
}

}  // namespace adb
