// Fuzz target: adb::io::loadMeshFromMemory in one format (ADB_FUZZ_FORMAT, the extension
// assimp's format hint takes). Every input must load as a valid mesh or get a MeshFileError,
// within seconds: any other exception, a crash, a sanitizer report or a hang is a finding.
#include <cstddef>
#include <cstdint>

#include "adb/io/mesh_file.h"

#ifndef ADB_FUZZ_FORMAT
#error "ADB_FUZZ_FORMAT names the format, e.g. \"ply\""
#endif
#ifndef ADB_FUZZ_ISOLATE
#define ADB_FUZZ_ISOLATE 1
#endif

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // Limits well below the defaults: the fuzzer's memory limit is 2 GB.
  adb::io::LoadLimits limits;
  limits.maxFileBytes = 1 << 20;
  limits.maxVertices = 1 << 20;
  limits.maxFaces = 1 << 20;
  limits.maxReadSeconds = 5;  // a reader that hangs is stopped and named sooner
  // OBJ and STL read in this process (ADB_FUZZ_ISOLATE 0): a fault in assimp's reader is then
  // a finding rather than a contained crash, and a fork per input no longer caps the rate.
  // glTF and 3MF, where assimp does crash, fuzz the isolated reader that applications get.
  limits.isolate = ADB_FUZZ_ISOLATE != 0;
  try {
    const adb::TriangleMesh mesh =
        adb::io::loadMeshFromMemory(data, size, ADB_FUZZ_FORMAT, "fuzz." ADB_FUZZ_FORMAT, nullptr, limits);
    // A mesh that loads is valid: at least one triangle, every index in range.
    if (mesh.triangleCount() == 0) __builtin_trap();
    for (const adb::Triangle& t : mesh.triangles()) {
      for (std::uint32_t v : t) {
        if (v >= mesh.vertices().size()) __builtin_trap();
      }
    }
  } catch (const adb::io::MeshFileError&) {
  }
  return 0;
}
