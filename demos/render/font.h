// Internal: a 5 x 7 bitmap font for captions, written in code (no font files to find).
#pragma once

#include <array>
#include <cstdint>

namespace adb::render::detail {

constexpr int kGlyphWidth = 5;
constexpr int kGlyphHeight = 7;

/// The glyph of `c`: 7 rows, bit 4 the leftmost column. Lower case is drawn as upper case;
/// a character without a glyph as '?'.
const std::array<std::uint8_t, kGlyphHeight>& glyph(char c);

}  // namespace adb::render::detail
