// Fuzz target: a tree built from raw bytes and queried against itself at a pose from the
// bytes. Layout (little endian; what is missing counts as zero):
//   8 bytes   settings: mode (even: ADB, odd: exact), k_min, p_min in percent, budget
//             exponent (node pairs 2^e, 0: none), stop-at-first-hit, triangles per leaf,
//             grid resolution, exact cell counting (odd)
//   7 doubles pose of the second copy: quaternion w x y z, translation x y z
//   u32 n, then n x 3 doubles: vertices
//   u32 m, then m x 3 u32: triangles
// Bad meshes, settings and poses must be refused with their exceptions (MeshError,
// SettingsError, PoseError); a query that runs must answer with a confidence in [0, 1].
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "adb/core/mesh.h"
#include "adb/core/query.h"
#include "adb/core/tree.h"

namespace {

class Bytes {
 public:
  Bytes(const std::uint8_t* data, std::size_t size) : m_data(data), m_size(size) {}
  template <class T>
  T take() {
    T value{};
    const std::size_t n = std::min(sizeof(T), m_size - m_at);
    if (n > 0) std::memcpy(&value, m_data + m_at, n);
    m_at += n;
    return value;
  }
  std::size_t left() const { return m_size - m_at; }

 private:
  const std::uint8_t* m_data;
  std::size_t m_size, m_at = 0;
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  Bytes in(data, size);
  std::uint8_t s[8];
  for (std::uint8_t& b : s) b = in.take<std::uint8_t>();
  double pose[7];
  for (double& p : pose) p = in.take<double>();
  // Counts are bounded by the bytes left: no allocation beyond the input's size.
  const std::uint32_t n = std::min<std::uint32_t>(in.take<std::uint32_t>(), static_cast<std::uint32_t>(in.left() / 24));
  std::vector<adb::Vec3> vertices(n);
  for (adb::Vec3& v : vertices) v = adb::Vec3(in.take<double>(), in.take<double>(), in.take<double>());
  const std::uint32_t m = std::min<std::uint32_t>(in.take<std::uint32_t>(), static_cast<std::uint32_t>(in.left() / 12));
  std::vector<adb::Triangle> triangles(m);
  for (adb::Triangle& t : triangles) t = {in.take<std::uint32_t>(), in.take<std::uint32_t>(), in.take<std::uint32_t>()};
  try {
    const adb::TriangleMesh mesh(std::move(vertices), std::move(triangles), "fuzz");
    adb::BuildSettings build;
    build.maxLeafTriangles = s[5] % 17;  // 0 and 16 are out of range: refused
    build.gridResolution = s[6] % 34;   // 0 and 33 likewise
    if (s[6] == 0) build.gridResolution = 8;
    if (s[7] % 2) build.counting = adb::CellCounting::Exact;
    const adb::AdbTree tree(mesh, build);
    adb::QuerySettings q;
    q.mode = s[0] % 2 ? adb::QueryMode::Exact : adb::QueryMode::Adb;
    q.kMin = s[1];
    q.pMin = s[2] / 100.0;
    if (s[3] % 40 > 0) q.budgetNodePairs = std::uint64_t(1) << (s[3] % 40);
    q.stopAtFirstHit = s[4] % 2 == 0;
    const adb::Pose b = adb::Pose::fromQuaternion(
        Eigen::Quaterniond(pose[0], pose[1], pose[2], pose[3]), adb::Vec3(pose[4], pose[5], pose[6]));
    adb::QueryScratch scratch;
    const adb::QueryResult r = adb::collide(tree, adb::Pose{}, tree, b, q, scratch);
    if (!(r.confidence >= 0.0 && r.confidence <= 1.0)) __builtin_trap();
  } catch (const adb::MeshError&) {
  } catch (const adb::SettingsError&) {
  } catch (const adb::PoseError&) {
  }
  return 0;
}
