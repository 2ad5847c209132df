#include "render/image.h"

#include <algorithm>

namespace adb::render {

Image::Image(int width, int height, Rgb fill)
    : m_width(std::max(1, width)),
      m_height(std::max(1, height)),
      m_pixels(static_cast<std::size_t>(m_width) * m_height, fill) {}

Image sideBySide(const std::vector<Image>& images, int gap, Rgb gapColour) {
  int width = 0, height = 0;
  for (const Image& i : images) {
    width += i.width();
    height = std::max(height, i.width() > 0 ? i.height() : 0);
  }
  width += gap * std::max(0, static_cast<int>(images.size()) - 1);
  Image out(width, height, gapColour);
  int left = 0;
  for (const Image& i : images) {
    for (int y = 0; y < i.height(); ++y) {
      for (int x = 0; x < i.width(); ++x) out.at(left + x, y) = i.at(x, y);
    }
    left += i.width() + gap;
  }
  return out;
}

}  // namespace adb::render
