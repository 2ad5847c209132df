#include "render/scene_picture.h"

#include <algorithm>
#include <cstdio>

#include "render/colour_map.h"
#include "render/rasterizer.h"

namespace adb::demo {
namespace {

constexpr render::Rgb kStatic{170, 170, 175};
constexpr render::Rgb kKinematic{90, 130, 200};

render::Rgb mix(render::Rgb a, render::Rgb b, double t) {
  auto channel = [t](std::uint8_t x, std::uint8_t y) {
    return static_cast<std::uint8_t>(std::clamp((1.0 - t) * x + t * y, 0.0, 255.0));
  };
  return {channel(a.r, b.r), channel(a.g, b.g), channel(a.b, b.b)};
}

// The lowest confidence among the overlapping pairs a body is in, or -1 when in none.
double overlapConfidence(const scene::SceneWorld& world, std::uint32_t body) {
  double confidence = -1.0;
  for (const scene::OverlapPair& p : world.overlapping()) {
    if (p.body0 != body && p.body1 != body) continue;
    confidence = confidence < 0 ? p.confidence : std::min(confidence, p.confidence);
  }
  return confidence;
}

render::Rgb bodyColour(const scene::SceneWorld& world, std::size_t i) {
  const scene::BodySpec& spec = world.scene().bodies[i];
  // Kinematic bodies are darker: they drive, they do not respond.
  render::Rgb base = spec.kind == scene::BodySpec::Kind::Static ? kStatic : render::bodyColour(i);
  if (spec.kind == scene::BodySpec::Kind::Kinematic) base = mix(base, kKinematic, 0.5);
  const double overlap = overlapConfidence(world, static_cast<std::uint32_t>(i));
  // Overlapping: red, the more so the surer the answer.
  if (overlap >= 0) base = mix(base, render::Rgb{230, 50, 40}, 0.3 + 0.5 * overlap);
  return base;
}

}  // namespace

render::Camera sceneCamera(const scene::SceneWorld& world) {
  const scene::ViewSpec& view = world.scene().view;
  if (view.given) return render::Camera{view.eye, view.target, Vec3::UnitY(), view.fovDegrees};
  Aabb bounds;
  for (std::size_t i = 0; i < world.bodyCount(); ++i) {
    if (world.scene().shapes[world.scene().bodies[i].shape].kind == scene::ShapeSpec::Kind::Plane) {
      continue;
    }
    const Pose pose = world.bodyPose(i);
    const Aabb& box = world.displayMesh(i).bounds();
    for (int c = 0; c < 8; ++c) {
      const Vec3 corner((c & 1) ? box.hi.x() : box.lo.x(), (c & 2) ? box.hi.y() : box.lo.y(),
                        (c & 4) ? box.hi.z() : box.lo.z());
      bounds.grow(pose.apply(corner));
    }
  }
  if (!(bounds.lo.array() <= bounds.hi.array()).all()) bounds = Aabb{Vec3::Zero(), Vec3::Zero()};
  return render::cameraFraming(bounds.lo, bounds.hi, Vec3(-0.55, -0.45, -1.0).normalized());
}

render::Image drawScene(const scene::SceneWorld& world, const render::Camera& camera, int width,
                        int height, const std::string& caption) {
  render::Rasterizer r(width, height);
  r.clear();
  r.setCamera(camera);
  for (std::size_t i = 0; i < world.bodyCount(); ++i) {
    const TriangleMesh& mesh = world.displayMesh(i);
    r.drawMesh(mesh.vertices(), mesh.triangles(), world.bodyPose(i), bodyColour(world, i));
  }
  for (const scene::CutPair& cut : world.cutPairs()) {
    r.drawSegment(world.bodyPose(cut.body0).translation, world.bodyPose(cut.body1).translation,
                  render::confidenceColour(cut.confidence));
  }
  for (const scene::ContactPoint& c : world.contacts()) {
    r.drawPoint(c.position, 3.5, render::confidenceColour(c.confidence));
  }
  // Twice the font's size where the caption fits the width (6 pixels a character at size 1).
  const int scale = static_cast<int>(caption.size()) * 12 <= width - 16 ? 2 : 1;
  r.drawText(8, 8, caption, render::Rgb{20, 20, 20}, scale);
  return r.image();
}

std::string sceneCaption(const scene::SceneWorld& world, double meanStepMillis) {
  const scene::StepRecord& r = world.last();
  const scene::BudgetSpec& b = world.scene().world.budget;
  char budget[64] = "";
  if (world.built().budget && b.kind == scene::BudgetSpec::Kind::Micros) {
    std::snprintf(budget, sizeof budget, " budget %.3g ms", b.micros / 1000.0);
  } else if (world.built().budget) {
    std::snprintf(budget, sizeof budget, " budget %llu pairs",
                  static_cast<unsigned long long>(b.nodePairs));
  }
  char text[200];
  // The mean over the run so far, as the comparison table gives it: the last step alone of
  // a pile asleep says 0.0 beside a table that says 39.7. No seconds: with them adb's caption
  // was too long for the large font of the others.
  std::snprintf(text, sizeof text, "%s%s  step %d  %.2f ms/step mean",
                toString(world.backend()), budget, r.step, meanStepMillis);
  return text;
}

}  // namespace adb::demo
