// Colours for pictures: confidence from red (unsure) through orange to green (certain), and a
// palette for bodies.
#pragma once

#include <cstddef>

#include "render/image.h"

namespace adb::render {

/// [0, 1] to red, orange, yellow, green; values outside are clamped, NaN counts as 0.
Rgb confidenceColour(double confidence);

/// A palette of distinct, light colours, cycled.
Rgb bodyColour(std::size_t index);

}  // namespace adb::render
