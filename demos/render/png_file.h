// PNG files through libpng.
#pragma once

#include <filesystem>

#include "render/image.h"

namespace adb::render {

/// Writes `image` as an 8-bit RGB PNG. Throws std::runtime_error naming the file (a missing
/// folder, a full disk, libpng's own complaint).
void writePng(const Image& image, const std::filesystem::path& file);

/// Reads an 8-bit RGB or RGBA PNG (alpha dropped). Throws std::runtime_error naming the file
/// when it is missing or not such a PNG.
Image readPng(const std::filesystem::path& file);

}  // namespace adb::render
