// The demo's pictures: PNG files read back as written, the rasterizer's depth order and
// clipping, colours, captions, and a gallery scene drawn at the stated size.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>

#include "adb/scene/scene_file.h"
#include "adb/scene/scene_world.h"
#include "adb/support/mesh_generators.h"
#include "render/colour_map.h"
#include "render/png_file.h"
#include "render/rasterizer.h"
#include "render/scene_picture.h"

namespace adb::render {
namespace {

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() /
                   ("adb_render_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

bool same(Rgb a, Rgb b) { return a.r == b.r && a.g == b.g && a.b == b.b; }

constexpr Rgb kBackground{245, 245, 245};

// A unit cube (half extent 0.5) drawn at `at`, seen from z = 5 looking at the origin.
Rasterizer cubes(const std::vector<std::pair<Vec3, Rgb>>& placed, int w = 160, int h = 120) {
  const TriangleMesh cube = gen::makeBox(Vec3::Constant(0.5), 1);
  Rasterizer r(w, h);
  r.clear(kBackground);
  r.setCamera(Camera{Vec3(0, 0, 5), Vec3::Zero(), Vec3::UnitY(), 40});
  for (const auto& [at, colour] : placed) {
    r.drawMesh(cube.vertices(), cube.triangles(), Pose{Mat3::Identity(), at}, colour);
  }
  return r;
}

TEST(Png, WrittenImagesReadBackPixelForPixel) {
  Image image(37, 23);
  for (int y = 0; y < 23; ++y) {
    for (int x = 0; x < 37; ++x) {
      image.at(x, y) = Rgb{static_cast<std::uint8_t>(7 * x), static_cast<std::uint8_t>(11 * y),
                           static_cast<std::uint8_t>(x ^ y)};
    }
  }
  const auto file = scratch("roundtrip.png");
  writePng(image, file);
  const Image back = readPng(file);
  ASSERT_EQ(back.width(), 37);
  ASSERT_EQ(back.height(), 23);
  for (std::size_t i = 0; i < image.pixels().size(); ++i) {
    ASSERT_TRUE(same(image.pixels()[i], back.pixels()[i])) << "pixel " << i;
  }
}

TEST(Png, AMissingFolderAndANonPngAreNamedErrors) {
  const auto missing = scratch("no/such/folder/x.png");
  try {
    writePng(Image(4, 4), missing);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(missing.string()), std::string::npos) << e.what();
  }
  const auto text = scratch("not.png");
  std::ofstream(text) << "not a picture at all";
  EXPECT_THROW(readPng(text), std::runtime_error);
  EXPECT_THROW(readPng(scratch("absent.png")), std::runtime_error);
}

TEST(Rasterizer, ACubeInFrontCoversTheCentreAndNotTheCorners) {
  const Rasterizer r = cubes({{Vec3::Zero(), Rgb{200, 40, 40}}});
  const Image& image = r.image();
  EXPECT_FALSE(same(image.at(80, 60), kBackground));
  EXPECT_GT(image.at(80, 60).r, image.at(80, 60).g);  // shaded, its own hue
  for (const auto& [x, y] : {std::pair{0, 0}, {159, 0}, {0, 119}, {159, 119}}) {
    EXPECT_TRUE(same(image.at(x, y), kBackground));
  }
}

TEST(Rasterizer, TheNearerOfTwoCubesWinsWhateverTheOrderDrawn) {
  const Rgb nearColour{40, 40, 200}, farColour{200, 40, 40};
  for (bool nearFirst : {true, false}) {
    std::vector<std::pair<Vec3, Rgb>> placed = {{Vec3(0, 0, 1), nearColour},
                                                {Vec3(0, 0, -1), farColour}};
    if (!nearFirst) std::swap(placed[0], placed[1]);
    const Rgb centre = cubes(placed).image().at(80, 60);
    EXPECT_GT(centre.b, centre.r) << (nearFirst ? "near first" : "far first");
  }
}

TEST(Rasterizer, BehindTheCameraDrawsNothingAndCrossingTheEyeDoesNotCrash) {
  const Rasterizer behind = cubes({{Vec3(0, 0, 8), Rgb{200, 40, 40}}});
  for (const Rgb& p : behind.image().pixels()) ASSERT_TRUE(same(p, kBackground));
  // A cube around the eye: clipped at the near plane, drawn where it is in front.
  const Rasterizer around = cubes({{Vec3(0, 0, 5), Rgb{200, 40, 40}}});
  EXPECT_FALSE(same(around.image().at(80, 60), kBackground));
  // Non-finite and huge coordinates are skipped, not drawn across the image.
  Rasterizer r(64, 48);
  r.clear(kBackground);
  r.setCamera(Camera{});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  r.drawMesh({Vec3(nan, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)}, {{0, 1, 2}, {0, 1, 7}}, Pose{},
             Rgb{1, 2, 3});
  r.drawPoint(Vec3(nan, nan, nan), 3, Rgb{1, 2, 3});
  r.drawSegment(Vec3(0, 0, 1e300), Vec3(0, 0, -1e300), Rgb{1, 2, 3});
}

TEST(Image, SideBySideIsTheWidthsPlusTheGaps) {
  const Image strip = sideBySide({Image(10, 5), Image(20, 8), Image(3, 2)}, 4);
  EXPECT_EQ(strip.width(), 10 + 20 + 3 + 2 * 4);
  EXPECT_EQ(strip.height(), 8);
}

TEST(ColourMap, RedWhenUnsureGreenWhenCertainAndNanIsNotACrash) {
  EXPECT_GT(confidenceColour(0.0).r, confidenceColour(0.0).g);
  EXPECT_GT(confidenceColour(1.0).g, confidenceColour(1.0).r);
  EXPECT_TRUE(same(confidenceColour(std::nan("")), confidenceColour(0.0)));
  EXPECT_TRUE(same(confidenceColour(7.0), confidenceColour(1.0)));
}

TEST(Rasterizer, TextStaysInsideItsBox) {
  Rasterizer r(200, 60);
  r.clear(kBackground);
  r.drawText(10, 20, "ADB 1.0 ms/step", Rgb{0, 0, 0}, 2);
  int inked = 0;
  for (int y = 0; y < 60; ++y) {
    for (int x = 0; x < 200; ++x) {
      if (same(r.image().at(x, y), kBackground)) continue;
      ++inked;
      EXPECT_TRUE(x >= 10 && x < 10 + 15 * 12 && y >= 20 && y < 20 + 14) << x << "," << y;
    }
  }
  EXPECT_GT(inked, 100);
}

TEST(ScenePicture, AGallerySceneIsDrawnAtTheStatedSizeAndWrittenAsAValidPng) {
  scene::SceneWorld world(scene::loadScene(ADB_SCENES_DIR "/gears_contacts.json"),
                          scene::Backend::Adb);
  for (int i = 0; i < 30; ++i) world.step();
  const Image picture = demo::drawScene(world, demo::sceneCamera(world), 320, 200, "gears");
  const auto file = scratch("gears.png");
  writePng(picture, file);
  const Image back = readPng(file);
  EXPECT_EQ(back.width(), 320);
  EXPECT_EQ(back.height(), 200);
  int drawn = 0;
  for (const Rgb& p : back.pixels()) drawn += same(p, kBackground) ? 0 : 1;
  EXPECT_GT(drawn, 320 * 200 / 20);  // the gears fill a good part of the view
}

}  // namespace
}  // namespace adb::render
