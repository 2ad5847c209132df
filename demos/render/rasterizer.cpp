#include "render/rasterizer.h"

#include <algorithm>
#include <cmath>

#include "render/font.h"

namespace adb::render {
namespace {

// Nothing nearer the eye than this is drawn: triangles are clipped at the plane.
constexpr double kNear = 1e-3;
constexpr double kAmbient = 0.35;
// An inverse depth no surface reaches: drawn over everything.
constexpr float kOnTop = 1e30f;

Rgb shade(Rgb c, double k) {
  auto ch = [k](std::uint8_t v) {
    return static_cast<std::uint8_t>(std::clamp(std::lround(v * k), 0L, 255L));
  };
  return {ch(c.r), ch(c.g), ch(c.b)};
}

// Sutherland-Hodgman against the near plane: a triangle becomes 0, 3 or 4 vertices.
int clipNear(const std::array<Vec3, 3>& in, std::array<Vec3, 4>& out) {
  int n = 0;
  for (int i = 0; i < 3; ++i) {
    const Vec3& p = in[i];
    const Vec3& q = in[(i + 1) % 3];
    const bool pIn = p.z() >= kNear, qIn = q.z() >= kNear;
    if (pIn) out[n++] = p;
    if (pIn != qIn) {
      const double t = (kNear - p.z()) / (q.z() - p.z());  // q.z != p.z: one side each
      out[n++] = p + t * (q - p);
    }
  }
  return n;
}

}  // namespace

Rasterizer::Rasterizer(int width, int height)
    : m_image(width, height),
      m_depth(static_cast<std::size_t>(m_image.width()) * m_image.height(), 0.0f) {
  setCamera(Camera{});
}

void Rasterizer::clear(Rgb background) {
  m_image = Image(m_image.width(), m_image.height(), background);
  std::fill(m_depth.begin(), m_depth.end(), 0.0f);
}

void Rasterizer::setCamera(const Camera& camera) {
  m_camera = camera;
  const Vec3 view = camera.target - camera.eye;
  m_forward = view.norm() > 0 ? Vec3(view.normalized()) : Vec3(-Vec3::UnitZ());
  Vec3 right = m_forward.cross(camera.up);
  if (right.norm() < 1e-9) right = m_forward.cross(Vec3::UnitX());
  m_right = right.normalized();
  m_up = m_right.cross(m_forward);
  const double fov = std::clamp(camera.fovYDegrees, 1.0, 170.0) * M_PI / 180.0;
  m_focal = 0.5 * m_image.height() / std::tan(0.5 * fov);
  // The light comes from behind the camera's right shoulder, a little from above.
  m_light = (-m_forward + 0.4 * m_up + 0.3 * m_right).normalized();
}

Vec3 Rasterizer::toCamera(const Vec3& w) const {
  const Vec3 d = w - m_camera.eye;
  return Vec3(d.dot(m_right), d.dot(m_up), d.dot(m_forward));
}

bool Rasterizer::project(const Vec3& c, Projected& out) const {
  if (!(c.z() >= kNear) || !c.allFinite()) return false;
  out = {0.5 * m_image.width() + m_focal * c.x() / c.z(),
         0.5 * m_image.height() - m_focal * c.y() / c.z(), 1.0 / c.z()};
  return std::isfinite(out.x) && std::isfinite(out.y);
}

void Rasterizer::fillTriangle(const Projected& a, const Projected& b, const Projected& c,
                              Rgb colour) {
  const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
  if (!(std::abs(area) > 1e-12)) return;
  const int w = m_image.width(), h = m_image.height();
  const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))));
  const int x1 = std::min(w - 1, static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}))));
  const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))));
  const int y1 = std::min(h - 1, static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}))));
  for (int y = y0; y <= y1; ++y) {
    const double py = y + 0.5;
    for (int x = x0; x <= x1; ++x) {
      const double px = x + 0.5;
      // Barycentric weights by edge functions; inside when all share the area's sign.
      const double wa = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) / area;
      const double wb = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) / area;
      const double wc = 1.0 - wa - wb;
      if (wa < 0 || wb < 0 || wc < 0) continue;
      // 1/z is linear in screen space.
      const auto inverse = static_cast<float>(wa * a.inverseDepth + wb * b.inverseDepth +
                                              wc * c.inverseDepth);
      float& depth = m_depth[static_cast<std::size_t>(y) * w + x];
      if (inverse <= depth) continue;
      depth = inverse;
      m_image.at(x, y) = colour;
    }
  }
}

void Rasterizer::drawMesh(const std::vector<Vec3>& vertices,
                          const std::vector<std::array<std::uint32_t, 3>>& triangles,
                          const Pose& pose, Rgb colour) {
  std::vector<Vec3> camera(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    camera[i] = toCamera(pose.apply(vertices[i]));
  }
  for (const auto& t : triangles) {
    if (t[0] >= camera.size() || t[1] >= camera.size() || t[2] >= camera.size()) continue;
    const std::array<Vec3, 3> corners = {camera[t[0]], camera[t[1]], camera[t[2]]};
    const Vec3 normal = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
    const double length = normal.norm();
    if (!(length > 0)) continue;
    // The light in camera coordinates; two-sided: a face lit from behind is lit the same.
    const Vec3 light(m_light.dot(m_right), m_light.dot(m_up), m_light.dot(m_forward));
    const double lambert = std::abs(normal.dot(light)) / length;
    const Rgb shaded = shade(colour, kAmbient + (1.0 - kAmbient) * lambert);
    std::array<Vec3, 4> clipped;
    const int n = clipNear(corners, clipped);
    std::array<Projected, 4> p;
    bool ok = n >= 3;
    for (int i = 0; i < n && ok; ++i) ok = project(clipped[i], p[i]);
    if (!ok) continue;
    fillTriangle(p[0], p[1], p[2], shaded);
    if (n == 4) fillTriangle(p[0], p[2], p[3], shaded);
  }
}

void Rasterizer::disc(double cx, double cy, double radius, Rgb colour, float inverseDepth) {
  const double r = std::clamp(radius, 0.5, 64.0);
  const int x0 = std::max(0, static_cast<int>(cx - r)), x1 = std::min(m_image.width() - 1, static_cast<int>(cx + r));
  const int y0 = std::max(0, static_cast<int>(cy - r)), y1 = std::min(m_image.height() - 1, static_cast<int>(cy + r));
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      const double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
      if (dx * dx + dy * dy > r * r) continue;
      // Hidden behind a surface more than 4 % of the distance nearer.
      if (m_depth[static_cast<std::size_t>(y) * m_image.width() + x] > inverseDepth * 1.04f) continue;
      m_image.at(x, y) = colour;
    }
  }
}

void Rasterizer::drawPoint(const Vec3& world, double radiusPixels, Rgb colour) {
  Projected p;
  if (!project(toCamera(world), p)) return;
  disc(p.x, p.y, radiusPixels, colour, static_cast<float>(p.inverseDepth));
}

void Rasterizer::drawSegment(const Vec3& a, const Vec3& b, Rgb colour) {
  std::array<Vec3, 3> ends = {toCamera(a), toCamera(b), Vec3::Zero()};
  // Clip the segment at the near plane.
  if (ends[0].z() < kNear && ends[1].z() < kNear) return;
  for (int i = 0; i < 2; ++i) {
    Vec3& p = ends[i];
    const Vec3& q = ends[1 - i];
    if (p.z() < kNear) p = p + (kNear - p.z()) / (q.z() - p.z()) * (q - p);
  }
  Projected pa, pb;
  if (!project(ends[0], pa) || !project(ends[1], pb)) return;
  const double length = std::hypot(pb.x - pa.x, pb.y - pa.y);
  // Far off screen ends are not walked pixel by pixel: at most a few screens' worth.
  const int steps = static_cast<int>(std::min(length, 4.0 * (m_image.width() + m_image.height())));
  for (int i = 0; i <= steps; ++i) {
    const double t = steps > 0 ? static_cast<double>(i) / steps : 0.0;
    disc(pa.x + t * (pb.x - pa.x), pa.y + t * (pb.y - pa.y), 1.0, colour, kOnTop);
  }
}

void Rasterizer::drawText(int x, int y, const std::string& text, Rgb colour, int scale) {
  const int s = std::clamp(scale, 1, 16);
  int left = x;
  for (char c : text) {
    const auto& rows = detail::glyph(c);
    for (int row = 0; row < detail::kGlyphHeight; ++row) {
      for (int col = 0; col < detail::kGlyphWidth; ++col) {
        if (!(rows[row] & (1u << (detail::kGlyphWidth - 1 - col)))) continue;
        for (int dy = 0; dy < s; ++dy) {
          for (int dx = 0; dx < s; ++dx) {
            const int px = left + col * s + dx, py = y + row * s + dy;
            if (m_image.contains(px, py)) m_image.at(px, py) = colour;
          }
        }
      }
    }
    left += (detail::kGlyphWidth + 1) * s;
  }
}

}  // namespace adb::render
