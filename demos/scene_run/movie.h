// A movie of rendered frames, when ffmpeg is on the PATH (an optional tool: the frames are
// the output, the movie a convenience).
#pragma once

#include <filesystem>
#include <string>

namespace adb::demo {

/// Encodes `frames`/NNNNN.png at `fps` into `movie` (H.264, yuv420p) with ffmpeg. Returns the
/// movie's path, or "" when ffmpeg is missing or failed (said on stderr).
std::string writeMovie(const std::filesystem::path& frames, int fps,
                       const std::filesystem::path& movie);

}  // namespace adb::demo
