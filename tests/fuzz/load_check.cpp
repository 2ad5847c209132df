// Loads every file given with adb::io::loadMesh as an application would (default limits, the
// isolated reader) and prints one line per file: seconds, path, and "ok T" (T triangles) or
// "error <message>". Exits 1 if any load ends in anything but a valid mesh or a MeshFileError.
// tests/fuzz/mutate_meshes.py runs it over mutated copies of real meshes.
//   adb-load-check FILE...
#include <chrono>
#include <cstdio>
#include <exception>
#include <string>

#include "adb/io/mesh_file.h"

namespace {

// "ok T", "error ...", or an empty string for a load that broke the contract.
std::string verdict(const char* path) {
  try {
    const adb::TriangleMesh mesh = adb::io::loadMesh(path);
    for (const adb::Triangle& t : mesh.triangles()) {
      for (std::uint32_t v : t) {
        if (v >= mesh.vertices().size()) return {};
      }
    }
    return mesh.triangleCount() == 0 ? std::string() : "ok " + std::to_string(mesh.triangleCount());
  } catch (const adb::io::MeshFileError& e) {
    return std::string("error ") + e.what();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: not a MeshFileError: %s\n", path, e.what());
    return {};
  }
}

}  // namespace

int main(int argc, char** argv) {
  int broken = 0;
  for (int i = 1; i < argc; ++i) {
    const auto start = std::chrono::steady_clock::now();
    std::string v = verdict(argv[i]);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (v.empty()) {
      ++broken;
      v = "BROKEN";
    }
    std::printf("%.3f\t%s\t%s\n", seconds, argv[i], v.c_str());
    std::fflush(stdout);
  }
  return broken == 0 ? 0 : 1;
}
