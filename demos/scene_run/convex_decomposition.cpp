// ConvexDecomposition through Bullet's HACD (libHACD of libbullet-extras-dev).
#include "convex_decomposition.h"

#include <HACD/hacdHACD.h>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

namespace adb::demo {

ConvexDecomposition decompose(const TriangleMesh& mesh, const DecompositionSettings& settings) {
  const auto t0 = std::chrono::steady_clock::now();
  // HACD normalises these arrays in place and back: it gets copies.
  std::vector<HACD::Vec3<HACD::Real>> points;
  points.reserve(mesh.vertices().size());
  for (const Vec3& v : mesh.vertices()) points.emplace_back(v.x(), v.y(), v.z());
  std::vector<HACD::Vec3<long>> triangles;
  triangles.reserve(mesh.triangleCount());
  for (const Triangle& t : mesh.triangles()) {
    triangles.emplace_back(static_cast<long>(t[0]), static_cast<long>(t[1]),
                           static_cast<long>(t[2]));
  }

  HACD::HACD hacd;
  hacd.SetPoints(points.data());
  hacd.SetNPoints(points.size());
  hacd.SetTriangles(triangles.data());
  hacd.SetNTriangles(triangles.size());
  hacd.SetCompacityWeight(settings.compacityWeight);
  hacd.SetVolumeWeight(settings.volumeWeight);
  hacd.SetNClusters(settings.minClusters);
  hacd.SetNVerticesPerCH(settings.maxHullVertices);
  hacd.SetConcavity(settings.concavity);
  hacd.SetAddExtraDistPoints(false);
  hacd.SetAddNeighboursDistPoints(false);
  hacd.SetAddFacesPoints(settings.facePoints);
  if (!hacd.Compute()) throw std::runtime_error("HACD failed on mesh '" + mesh.name() + "'");

  ConvexDecomposition result;
  for (std::size_t c = 0; c < hacd.GetNClusters(); ++c) {
    // Flat clusters are kept too: with its margin a flat hull still stops bodies.
    const std::size_t n = hacd.GetNPointsCH(c);
    if (n == 0) continue;
    std::vector<HACD::Vec3<HACD::Real>> hullPoints(n);
    std::vector<HACD::Vec3<long>> hullTriangles(hacd.GetNTrianglesCH(c));
    hacd.GetCH(c, hullPoints.data(), hullTriangles.data());
    std::vector<Vec3>& hull = result.hulls.emplace_back();
    hull.reserve(n);
    for (const auto& p : hullPoints) hull.emplace_back(p.X(), p.Y(), p.Z());
    // Divergence theorem over the hull's closed surface; its winding is HACD's, so the sign
    // is dropped.
    double sixVolume = 0.0;
    for (const auto& t : hullTriangles) {
      const auto corner = [&](long i) -> const Vec3& { return hull[static_cast<std::size_t>(i)]; };
      sixVolume += corner(t.X()).dot(corner(t.Y()).cross(corner(t.Z())));
    }
    result.hullVolume += std::abs(sixVolume) / 6.0;
  }
  if (result.hulls.empty()) {
    throw std::runtime_error("HACD returned no hull for mesh '" + mesh.name() + "'");
  }
  result.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return result;
}

}  // namespace adb::demo
