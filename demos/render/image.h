// An RGB image in memory: what the rasterizer draws into and png_file.h writes.
#pragma once

#include <cstdint>
#include <vector>

namespace adb::render {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

class Image {
 public:
  /// width and height are clamped to at least 1.
  Image(int width, int height, Rgb fill = {255, 255, 255});
  int width() const { return m_width; }
  int height() const { return m_height; }
  /// (0, 0) is the top left; unchecked (callers clip).
  Rgb& at(int x, int y) { return m_pixels[static_cast<std::size_t>(y) * m_width + x]; }
  const Rgb& at(int x, int y) const { return m_pixels[static_cast<std::size_t>(y) * m_width + x]; }
  bool contains(int x, int y) const { return x >= 0 && y >= 0 && x < m_width && y < m_height; }
  const std::vector<Rgb>& pixels() const { return m_pixels; }

 private:
  int m_width, m_height;
  std::vector<Rgb> m_pixels;
};

/// The images left to right with `gap` pixels between them, on `gapColour`; shorter ones are
/// padded below.
Image sideBySide(const std::vector<Image>& images, int gap = 8, Rgb gapColour = {255, 255, 255});

}  // namespace adb::render
