// Fuzz target: scene files. Every input is read into a scene or refused with one SceneError;
// a small scene that reads (primitives and generated meshes, no files) is also built with
// every backend and stepped a few times: nothing may crash, hang or leave a NaN in a pose.
#include <cstddef>
#include <cstdint>
#include <string>

#include "adb/scene/scene_file.h"
#include "adb/scene/scene_world.h"

namespace {

// Small enough to build and step within the fuzzer's time per input.
bool small(const adb::scene::Scene& s) {
  std::size_t triangles = 0;
  for (const adb::scene::ShapeSpec& shape : s.shapes) {
    if (shape.kind == adb::scene::ShapeSpec::Kind::Mesh) return false;
    if (shape.kind == adb::scene::ShapeSpec::Kind::Generated) triangles += shape.triangles;
  }
  return triangles <= 20000 && s.bodies.size() <= 20;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  adb::scene::Scene scene;
  try {
    scene = adb::scene::parseScene(text, "fuzz.json");
  } catch (const adb::scene::SceneError&) {
    return 0;
  }
  if (!small(scene)) return 0;
  for (adb::scene::Backend backend : {adb::scene::Backend::Adb, adb::scene::Backend::GImpact}) {
    try {
      adb::scene::SceneWorld world(scene, backend);
      for (int i = 0; i < 3; ++i) world.step();
    } catch (const adb::scene::SceneError&) {
      return 0;  // a generated model the generator refuses, named by its shape
    }
  }
  return 0;
}
