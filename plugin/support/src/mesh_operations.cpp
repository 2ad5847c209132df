// Operations on generated meshes: merging several, moving one.
#include "adb/support/mesh_generators.h"

#include <cstdint>
#include <string>
#include <vector>

#include "generator_kit.h"

namespace adb::gen {
using namespace kit;  // the generators' shared parts

TriangleMesh merge(const std::vector<TriangleMesh>& meshes, const std::string& name) {
  require(!meshes.empty(), "merge", "no meshes to merge");
  std::vector<Vec3> vertices;
  std::vector<Triangle> triangles;
  for (const TriangleMesh& mesh : meshes) {
    const auto base = static_cast<std::uint32_t>(vertices.size());
    vertices.insert(vertices.end(), mesh.vertices().begin(), mesh.vertices().end());
    for (const Triangle& t : mesh.triangles()) {
      triangles.push_back({base + t[0], base + t[1], base + t[2]});
    }
  }
  return TriangleMesh(std::move(vertices), std::move(triangles), name);
}

TriangleMesh transformed(const TriangleMesh& mesh, const Pose& pose) {
  std::vector<Vec3> vertices;
  vertices.reserve(mesh.vertices().size());
  for (const Vec3& v : mesh.vertices()) vertices.push_back(pose.apply(v));
  return TriangleMesh(std::move(vertices), mesh.triangles(), mesh.name());
}

}  // namespace adb::gen
