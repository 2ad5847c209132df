// Shared helpers of the core tests: the brute-force oracle, fixed-seed poses, tolerances.
#pragma once

#include <random>

#include "adb/support/benchmark_poses.h"
#include "adb/core/mesh.h"
#include "adb/core/query.h"
#include "adb/core/triangle_test.h"

namespace adb::test {

/// Every seed in the tests is fixed: a failure reproduces.
inline constexpr std::uint64_t kSeed = 20261121;

/// The oracle: all triangle pairs of the two posed meshes, no hierarchy, no early culling
/// beyond the exact test itself. O(n m): keep meshes small.
inline bool bruteForceCollide(const TriangleMesh& a, const Pose& pa, const TriangleMesh& b,
                              const Pose& pb) {
  std::vector<Vec3> wb(b.vertices().size());
  for (std::size_t i = 0; i < wb.size(); ++i) wb[i] = pb.apply(b.vertices()[i]);
  for (const Triangle& ta : a.triangles()) {
    const Vec3 a0 = pa.apply(a.vertices()[ta[0]]), a1 = pa.apply(a.vertices()[ta[1]]),
               a2 = pa.apply(a.vertices()[ta[2]]);
    for (const Triangle& tb : b.triangles()) {
      if (trianglesIntersect(a0, a1, a2, wb[tb[0]], wb[tb[1]], wb[tb[2]])) return true;
    }
  }
  return false;
}

/// The oracle's count: intersecting triangle pairs of the two posed meshes, all pairs tried.
inline std::size_t bruteForceIntersectingPairs(const TriangleMesh& a, const Pose& pa,
                                               const TriangleMesh& b, const Pose& pb) {
  std::size_t count = 0;
  for (const Triangle& ta : a.triangles()) {
    const Vec3 a0 = pa.apply(a.vertices()[ta[0]]), a1 = pa.apply(a.vertices()[ta[1]]),
               a2 = pa.apply(a.vertices()[ta[2]]);
    for (const Triangle& tb : b.triangles()) {
      count += trianglesIntersect(a0, a1, a2, pb.apply(b.vertices()[tb[0]]),
                                  pb.apply(b.vertices()[tb[1]]), pb.apply(b.vertices()[tb[2]]));
    }
  }
  return count;
}

inline QuerySettings exactSettings() {
  QuerySettings s;
  s.mode = QueryMode::Exact;
  return s;
}

/// Exact mode collecting every hit as a witness (no first-hit stop, no cap in practice).
inline QuerySettings collectEverySettings() {
  QuerySettings s = exactSettings();
  s.stopAtFirstHit = false;
  s.maxWitnesses = 100000;
  return s;
}

inline QuerySettings adbSettings(double pMin = 0.99, int kMin = 10) {
  QuerySettings s;
  s.mode = QueryMode::Adb;
  s.pMin = pMin;
  s.kMin = kMin;
  return s;
}

}  // namespace adb::test
