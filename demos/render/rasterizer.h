// A small software rasterizer for headless pictures: z-buffered, flat-shaded triangles, and
// points, segments and text drawn on top. No OpenGL context to find on a build machine.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "adb/core/geometry.h"
#include "render/camera.h"
#include "render/image.h"

namespace adb::render {

class Rasterizer {
 public:
  Rasterizer(int width, int height);

  /// Fills the image with `background` and clears the depth buffer.
  void clear(Rgb background = {245, 245, 245});
  void setCamera(const Camera& camera);

  /// Triangles given in the body's frame, placed by `pose` (body to world): flat Lambert
  /// shading under a light from behind the camera plus ambient, two-sided, depth-tested.
  /// Parts behind the camera are clipped away.
  void drawMesh(const std::vector<Vec3>& vertices,
                const std::vector<std::array<std::uint32_t, 3>>& triangles, const Pose& pose,
                Rgb colour);
  /// A filled disc, hidden only where a surface lies clearly in front of it (contact points
  /// lie on surfaces: they must not lose to the surface they lie on).
  void drawPoint(const Vec3& world, double radiusPixels, Rgb colour);
  /// A line two pixels wide on top of everything: a pair the budget cut.
  void drawSegment(const Vec3& a, const Vec3& b, Rgb colour);
  /// Text in the built-in 5 x 7 font, each font pixel `scale` pixels wide, the upper left
  /// corner at (x, y).
  void drawText(int x, int y, const std::string& text, Rgb colour, int scale = 2);

  const Image& image() const { return m_image; }

 private:
  struct Projected {
    double x, y, inverseDepth;
  };
  Vec3 toCamera(const Vec3& world) const;
  bool project(const Vec3& camera, Projected& out) const;
  void fillTriangle(const Projected& a, const Projected& b, const Projected& c, Rgb colour);
  void disc(double cx, double cy, double radius, Rgb colour, float inverseDepth);

  Image m_image;
  std::vector<float> m_depth;  // inverse depth per pixel: larger is nearer, 0 is empty
  Camera m_camera;
  Vec3 m_right, m_up, m_forward, m_light;
  double m_focal = 1.0;
};

}  // namespace adb::render
