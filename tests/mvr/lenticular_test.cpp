// The panel mapping of a lenticular display (mvr/lenticular.h, issue 48):
// a small panel's views computed by hand, each channel from its own
// subpixel's view (flipSubp swapping red and blue), the image flips, the
// GL pass equal to its CPU twin on every subpixel, and bad calibration
// files as one-line errors.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>

#include <nlohmann/json.hpp>

#include "mvr/error.h"
#include "mvr/gl/lenticular_pass.h"
#include "mvr/images/panel_calibration.h"
#include "mvr/lenticular.h"
#include "tests/support/file_test.h"
#include "tests/support/gl_fixture.h"

namespace mvr {
namespace {

// A 4 x 2 panel whose lenses cross it once (DPI 4, pitch sqrt 2 at slope
// 1: pitch' = sqrt 2 * 4 / 4 * cos 45 deg = 1) with tilt 2 / (4 * 1) =
// 0.5 and centre 0.05, showing 4 views: z_i = fract(u + i / 12 + v / 2 -
// 0.05). Pixel (0, 0): u = 0.125, v = 0.75, z = 0.45, 0.533, 0.617: views
// 1, 2, 2 (floor 4z). No z lands within 0.03 of a view's edge.
PanelCalibration smallPanel() {
  PanelCalibration c;
  c.pitch = std::sqrt(2.0), c.slope = 1.0, c.center = 0.05, c.dpi = 4.0;
  c.screenW = 4, c.screenH = 2;
  return c;
}

// The 2 x 2 quilt of 1-pixel tiles: view v's colour (10 + v, 20 + v, 30 + v).
// View 0 is the bottom-left tile: rows top first, views 2, 3 then 0, 1.
Image tinyQuilt() {
  Image q(2, 2, PixelType::Srgb8);
  const int viewAt[4] = {2, 3, 0, 1};
  for (int p = 0; p < 4; ++p) {
    const int v = viewAt[p];
    q.bytes[4 * size_t(p) + 0] = uint8_t(10 + v), q.bytes[4 * size_t(p) + 1] = uint8_t(20 + v);
    q.bytes[4 * size_t(p) + 2] = uint8_t(30 + v), q.bytes[4 * size_t(p) + 3] = 255;
  }
  return q;
}

TEST(Lenticular, ViewsOfASmallPanelByHand) {
  PanelCalibration c = smallPanel();
  const QuiltGrid grid{2, 2, 4, 1, 1};
  // [y][x][i], by hand (z as in smallPanel's comment).
  const int want[2][4][3] = {{{1, 2, 2}, {2, 3, 3}, {3, 0, 0}, {0, 1, 1}}, {{0, 1, 1}, {1, 2, 2}, {2, 3, 3}, {3, 0, 0}}};
  const LenticularMap m = LenticularMap::of(c, grid, 2);
  EXPECT_FLOAT_EQ(m.pitch, 1.0f);
  EXPECT_FLOAT_EQ(m.tilt, 0.5f);
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 4; ++x)
      for (int i = 0; i < 3; ++i) EXPECT_EQ(m.view(x, y, i), want[y][x][i]) << x << "," << y << " subpixel " << i;
  // invView: z -> 1 - z; pixel (0, 0): 0.55, 0.467, 0.383: views 2, 1, 1.
  c.invView = true;
  const LenticularMap inverted = LenticularMap::of(c, grid, 2);
  EXPECT_EQ(inverted.view(0, 0, 0), 2);
  EXPECT_EQ(inverted.view(0, 0, 1), 1);
  EXPECT_EQ(inverted.view(0, 0, 2), 1);
  EXPECT_EQ(inverted.view(2, 0, 1), 3);  // 1 - 0.033
}

// Red from subpixel 0's view, green from 1's, blue from 2's; flipSubp
// takes red from 2 and blue from 0.
TEST(Lenticular, EachChannelComesFromItsSubpixelsView) {
  PanelCalibration c = smallPanel();
  const Image quilt = tinyQuilt();
  const Image a = nativeImage(quilt, LenticularMap::of(c, {2, 2, 4, 1, 1}, 2));
  ASSERT_EQ(a.width, 4);
  ASSERT_EQ(a.height, 2);
  // Pixel (0, 0): views 1, 2, 2.
  EXPECT_EQ(a.bytes[0], 11);
  EXPECT_EQ(a.bytes[1], 22);
  EXPECT_EQ(a.bytes[2], 32);
  EXPECT_EQ(a.bytes[3], 255);
  // Pixel (2, 1) (row 1, the bottom): views 2, 3, 3.
  const uint8_t* p = &a.bytes[4 * (4 + 2)];
  EXPECT_EQ(p[0], 12);
  EXPECT_EQ(p[1], 23);
  EXPECT_EQ(p[2], 33);
  c.flipSubp = true;
  const Image b = nativeImage(quilt, LenticularMap::of(c, {2, 2, 4, 1, 1}, 2));
  EXPECT_EQ(b.bytes[0], 12);  // red from subpixel 2: view 2
  EXPECT_EQ(b.bytes[1], 22);
  EXPECT_EQ(b.bytes[2], 31);  // blue from subpixel 0: view 1
}

// Within a tile: u' = 1 - u with flipImageX (the lens phase moves with
// it), v' = 1 - v for the sample only with flipImageY.
TEST(Lenticular, ImageFlipsMirrorTheSampleInTheTile) {
  PanelCalibration c = smallPanel();
  const QuiltGrid grid{2, 2, 4, 4, 2};  // tiles of 4 x 2: one texel per panel pixel
  const LenticularMap plain = LenticularMap::of(c, grid, 4);
  // Pixel (0, 0): view 1 (tile column 1, bottom row of tiles), texel (0, top row of the tile).
  EXPECT_EQ(plain.texel(0, 0, 0), glm::ivec2(4 + 0, 4 - 1 - 1));
  c.flipImageY = true;
  const LenticularMap flippedY = LenticularMap::of(c, grid, 4);
  EXPECT_EQ(flippedY.view(0, 0, 0), 1);                          // the phase keeps v
  EXPECT_EQ(flippedY.texel(0, 0, 0), glm::ivec2(4 + 0, 4 - 1));  // the tile's bottom row
  c.flipImageY = false, c.flipImageX = true;
  const LenticularMap flippedX = LenticularMap::of(c, grid, 4);
  // u' = 0.875: z = 0.875 + 0.375 - 0.05 = 1.2 -> 0.2: view 0, texel column 3.
  EXPECT_EQ(flippedX.view(0, 0, 0), 0);
  EXPECT_EQ(flippedX.texel(0, 0, 0), glm::ivec2(3, 4 - 1 - 1));
}

class LenticularGl : public test::GlTest {};

// A Portrait's calibration (Looking Glass Portrait: 1536 x 2048 at 324
// DPI) on a quarter of its panel, mapping a 48-view quilt of random texels:
// the GL pass and the CPU agree on every subpixel, with each flag set.
TEST_F(LenticularGl, PassEqualsTheCpuOnEverySubpixel) {
  PanelCalibration c;
  c.pitch = 52.58737564086914, c.slope = -7.196136474609375, c.center = 0.4321881363063158;
  c.dpi = 324.0 / 4, c.screenW = 1536 / 4, c.screenH = 2048 / 4, c.invView = true;
  const QuiltGrid grid{8, 6, 48, 105, 140};
  Image quilt(8 * 105, 6 * 140, PixelType::Srgb8);
  std::mt19937 random(7);
  for (uint8_t& b : quilt.bytes) b = uint8_t(random());
  for (int variant = 0; variant < 4; ++variant) {
    c.flipSubp = variant == 1, c.flipImageX = variant == 2, c.flipImageY = variant == 3;
    c.invView = variant != 3;
    const LenticularMap map = LenticularMap::of(c, grid, quilt.height);
    const Image cpu = nativeImage(quilt, map);
    const Image gpu = LenticularPass(map).render(quilt);
    ASSERT_EQ(gpu.bytes.size(), cpu.bytes.size());
    size_t differ = 0;
    for (size_t k = 0; k < cpu.bytes.size(); ++k) differ += cpu.bytes[k] != gpu.bytes[k];
    EXPECT_EQ(differ, 0u) << "variant " << variant;
  }
}

// The views as an EPI volume (what mvr live uploads): the same native
// image as from the quilt, on every subpixel, and so does a view array;
// and the volume is the quilt's views, scanline by scanline.
TEST_F(LenticularGl, EpiVolumeAndViewArrayGiveTheQuiltsImage) {
  PanelCalibration c;
  c.pitch = 52.58737564086914, c.slope = -7.196136474609375, c.center = 0.4321881363063158;
  c.dpi = 324.0 / 8, c.screenW = 1536 / 8, c.screenH = 2048 / 8, c.invView = true, c.flipImageY = true;
  const QuiltGrid grid{4, 3, 10, 24, 32};  // two tiles empty
  Image quilt(4 * 24, 3 * 32, PixelType::Srgb8);
  std::mt19937 random(11);
  for (uint8_t& b : quilt.bytes) b = uint8_t(random());
  const Image volume = epiVolumeOf(quilt, grid);
  // View 5 (second tile row from the bottom, second column), its scanline 7.
  EXPECT_EQ(0, std::memcmp(volume.row(7 * 10 + 5), quilt.row(32 + 7) + 4 * 24, volume.rowBytes()));
  const LenticularMap map = LenticularMap::of(c, grid, quilt.height);
  const Image cpu = nativeImage(quilt, map);
  EXPECT_EQ(LenticularPass(map, ViewLayout::EpiVolume).render(volume).bytes, cpu.bytes);
  EXPECT_EQ(LenticularPass(map, ViewLayout::Quilt).render(quilt).bytes, cpu.bytes);
  // The views one under another (a view array's layers), from the volume.
  Image views(24, 32 * 10, PixelType::Srgb8);
  for (int v = 0; v < 10; ++v)
    for (int r = 0; r < 32; ++r) std::memcpy(views.row(v * 32 + r), volume.row(r * 10 + v), views.rowBytes());
  EXPECT_EQ(LenticularPass(map, ViewLayout::ViewArray).render(views).bytes, cpu.bytes);
}

class Calibration : public test::FileTest {};

TEST_F(Calibration, ReadsNumbersAndValueObjects) {
  const std::string path = write("visual.json", R"({"pitch": {"value": 50}, "slope": -5, "center": {"value": 0.25},
    "DPI": 300, "screenW": {"value": 1440}, "screenH": 2560, "invView": {"value": 1}, "flipSubp": 1})");
  const PanelCalibration c = readCalibration(path);
  EXPECT_EQ(c.pitch, 50.0);
  EXPECT_EQ(c.slope, -5.0);
  EXPECT_EQ(c.center, 0.25);
  EXPECT_EQ(c.screenW, 1440);
  EXPECT_TRUE(c.invView);
  EXPECT_TRUE(c.flipSubp);
  EXPECT_FALSE(c.flipImageX);
  EXPECT_EQ(c.viewCone, 40.0);
  EXPECT_DOUBLE_EQ(c.pitchAcross(), 50.0 * 1440 / 300 * std::cos(std::atan(-0.2)));
  EXPECT_DOUBLE_EQ(c.tilt(), 2560.0 / (1440 * -5.0));
}

TEST_F(Calibration, BadFilesAreOneLineErrors) {
  const std::string good = R"("pitch": 50, "slope": -5, "center": 0.2, "screenW": 1440, "screenH": 2560, "invView": 1)";
  struct Case {
    std::string text, message;
  };
  for (const Case& c : {Case{"{" + good + "}", "calibration has no DPI"},
                        Case{"{" + good + R"(, "DPI": 0})", "DPI must be above 0"},
                        Case{R"({"pitch": 50, "slope": 0, "center": 0.2, "screenW": 1440, "screenH": 2560,
                                "invView": 1, "DPI": 300})", "slope must not be 0"},
                        Case{"{" + good + R"(, "DPI": {"value": "wide"}})", "DPI is not a finite number"},
                        Case{"{" + good + R"(, "DPI": null})", "DPI is not a finite number"},
                        Case{R"({"pitch": 50, "slope": -5, "center": 0.2, "screenW": 0, "screenH": 2560,
                                "invView": 1, "DPI": 300})", "screenW must be a whole number of pixels"},
                        Case{"[1, 2]", "must be a JSON object"},
                        Case{"{ not json", "is not JSON"}}) {
    const std::string path = write("bad.json", c.text);
    test::expectOneLineError([&] { readCalibration(path); }, path, c.message);
  }
  test::expectOneLineError([&] { readCalibration((dir_ / "none.json").string()); }, "none.json", "cannot open");
}

}  // namespace
}  // namespace mvr
