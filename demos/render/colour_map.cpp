#include "render/colour_map.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace adb::render {
namespace {

std::uint8_t lerp(std::uint8_t a, std::uint8_t b, double t) {
  return static_cast<std::uint8_t>(std::lround(a + (b - a) * t));
}

}  // namespace

Rgb confidenceColour(double confidence) {
  const double c = std::isnan(confidence) ? 0.0 : std::clamp(confidence, 0.0, 1.0);
  // Red at 0, yellow at 0.5, green at 1: a reader sees doubt as heat.
  constexpr Rgb red{215, 40, 30}, yellow{240, 200, 30}, green{40, 170, 60};
  if (c < 0.5) return {lerp(red.r, yellow.r, 2 * c), lerp(red.g, yellow.g, 2 * c), lerp(red.b, yellow.b, 2 * c)};
  const double t = 2 * c - 1;
  return {lerp(yellow.r, green.r, t), lerp(yellow.g, green.g, t), lerp(yellow.b, green.b, t)};
}

Rgb bodyColour(std::size_t index) {
  static constexpr std::array<Rgb, 8> kPalette = {{{230, 159, 100},
                                                   {120, 180, 220},
                                                   {170, 210, 120},
                                                   {220, 140, 180},
                                                   {240, 210, 110},
                                                   {160, 150, 220},
                                                   {120, 200, 190},
                                                   {200, 170, 140}}};
  return kPalette[index % kPalette.size()];
}

}  // namespace adb::render
