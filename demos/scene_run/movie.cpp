#include "scene_run/movie.h"

#include <cstdio>
#include <cstdlib>

namespace adb::demo {
namespace {

bool haveFfmpeg() { return std::system("command -v ffmpeg > /dev/null 2>&1") == 0; }

// Single quotes around a path for the shell, its own quotes escaped.
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

std::string writeMovie(const std::filesystem::path& frames, int fps,
                       const std::filesystem::path& movie) {
  if (!haveFfmpeg()) {
    std::fprintf(stderr, "adb-demo: no ffmpeg on the PATH: frames only, no movie\n");
    return "";
  }
  // Even sizes: yuv420p needs them.
  const std::string command = "ffmpeg -y -loglevel error -framerate " + std::to_string(fps) +
                              " -i " + quoted((frames / "%05d.png").string()) +
                              " -vf 'pad=ceil(iw/2)*2:ceil(ih/2)*2' -pix_fmt yuv420p " +
                              quoted(movie.string());
  if (std::system(command.c_str()) != 0) {
    std::fprintf(stderr, "adb-demo: ffmpeg failed: %s\n", command.c_str());
    return "";
  }
  return movie.string();
}

}  // namespace adb::demo
