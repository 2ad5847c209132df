// Internal: doubles in error messages.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace adb::detail {

/// A double for an error message: %g, so that 1e-15 reads "1e-15" and 1e300 "1e+300"
/// (std::to_string prints "0.000000" and 300 digits). More digits only where %g's 6 would not
/// round-trip, so that 1.0000001 is not shown as the limit "1" it exceeds.
inline std::string formatNumber(double x) {
  char text[32];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(text, sizeof text, "%.*g", digits, x);
    // Non-finite values (NaN, inf) never compare equal: they print at 6 digits.
    if (!std::isfinite(x) || std::strtod(text, nullptr) == x) break;
  }
  return text;
}

/// Largest coordinate magnitude a mesh vertex or a pose translation may have: the box centre
/// (lo + hi) / 2 overflows near DBL_MAX, and a query squares the distance between two tree
/// origins, which overflows past 1.3e154 and then culls nothing. 1e150 leaves room for poses
/// 1000 times further out than the mesh. No mesh of a supported extent (<= 1e12) resolves in
/// double beyond ~1e28 from the origin, so this refuses only points and flat far meshes.
inline constexpr double kMaxCoordinate = 1e150;

}  // namespace adb::detail
