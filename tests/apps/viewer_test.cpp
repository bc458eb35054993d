// The viewer under a virtual X display: its screenshot shows the chosen
// view pixel for pixel, and below it the EPI of the chosen scanline.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>

#include "mvr/image.h"
#include "mvr/images/compare.h"
#include "mvr/images/image_file.h"
#include "tests/support/cli.h"
#include "tests/support/gl_fixture.h"

namespace mvr {
namespace {

// What the viewer shows of a stored pixel: over black, opaque (the sets
// here have hard edges, alpha 0 or 1).
Image overBlack(const Image& in) {
  Image out = in;
  for (size_t i = 0; i < out.bytes.size(); i += 4) {
    if (out.bytes[i + 3] == 0) out.bytes[i] = out.bytes[i + 1] = out.bytes[i + 2] = 0;
    out.bytes[i + 3] = 255;
  }
  return out;
}

bool haveXvfb() { return std::system("command -v xvfb-run >/dev/null 2>&1") == 0; }

TEST(Viewer, ScreenshotShowsTheViewAndItsEpi) {
  if (!haveXvfb()) GTEST_SKIP() << "no xvfb-run";
  auto set = test::freshDir("viewer_set");
  ASSERT_TRUE(test::succeeded(test::runMvr("render --views 7 --size 64x48 --out " + set.string())));
  const std::string shot = (set / "shot.png").string();
  auto r = test::shell("xvfb-run -a " + test::mvrBinary() + " view " + set.string() +
                       " --view 3 --scanline 30 --screenshot " + shot);
  ASSERT_TRUE(test::succeeded(r));
  Image s = readImage(shot);
  ASSERT_EQ(s.width, 64);
  ASSERT_EQ(s.height, 48 + 7);
  Image view = overBlack(readImage((set / "view_0003.png").string()));
  for (int y = 0; y < 48; ++y) ASSERT_EQ(0, std::memcmp(s.row(y), view.row(y), view.rowBytes())) << y;
  for (int i = 0; i < 7; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "view_%04d.png", i);
    Image vi = overBlack(readImage((set / name).string()));
    ASSERT_EQ(0, std::memcmp(s.row(48 + i), vi.row(30), vi.rowBytes())) << "EPI row " << i;
  }
}

// A scene is rendered with the camera options as mvr render renders it:
// the middle view shown is render's, byte for byte, and not the view
// without them; the options are refused for a rendered set.
TEST(Viewer, RendersASceneWithTheCameraOptionsAsRenderDoes) {
  if (!haveXvfb()) GTEST_SKIP() << "no xvfb-run";
  auto dir = test::freshDir("viewer_camera");
  const std::string scene = test::assetsDir() + "/default.json", camera = " --cone 30 --focal center --depthiness 1.5";
  ASSERT_TRUE(test::succeeded(test::runMvr("render " + scene + " --views 5 --size 64x48" + camera + " --out " + (dir / "set").string())));
  Image shots[2];
  for (int k = 0; k < 2; ++k) {
    const std::string shot = (dir / ("shot" + std::to_string(k) + ".png")).string();
    auto r = test::shell("xvfb-run -a " + test::mvrBinary() + " view " + scene +
                         " --views 5 --size 64x48 --view 2 --scanline 20 --screenshot " + shot +
                         (k == 0 ? camera : ""));
    ASSERT_TRUE(test::succeeded(r));
    shots[k] = readImage(shot);
  }
  const Image view = overBlack(readImage((dir / "set" / "view_0002.png").string()));
  ASSERT_EQ(shots[0].width, 64);
  for (int y = 0; y < 48; ++y) ASSERT_EQ(0, std::memcmp(shots[0].row(y), view.row(y), view.rowBytes())) << y;
  EXPECT_NE(shots[1].bytes, shots[0].bytes);
  auto r = test::shell("env -u DISPLAY " + test::mvrBinary() + " view " + (dir / "set").string() + " --cone 30");
  EXPECT_TRUE(test::exitedWith(r, 1));
  EXPECT_NE(r.err.find("--cone: applies to a scene"), std::string::npos) << r.err;
}

// A quilt opens as its views; with no --view or --scanline the viewer
// starts on the middle view and the middle of the object's rows.
TEST(Viewer, OpensAQuiltOnTheMiddleOfTheObject) {
  if (!haveXvfb()) GTEST_SKIP() << "no xvfb-run";
  auto set = test::freshDir("viewer_quilt");
  ASSERT_TRUE(test::succeeded(test::runMvr("render --views 6 --size 32x24 --quilt 3x2 --out " + set.string())));
  const std::string shot = (set / "shot.png").string();
  auto r = test::shell("xvfb-run -a " + test::mvrBinary() + " view " + (set / "quilt_qs3x2a1.33.png").string() +
                       " --screenshot " + shot);
  ASSERT_TRUE(test::succeeded(r));
  const Image s = readImage(shot);
  ASSERT_EQ(s.width, 32);
  ASSERT_EQ(s.height, 24 + 6);
  const Image middle = overBlack(readImage((set / "view_0003.png").string()));
  for (int y = 0; y < 24; ++y) ASSERT_EQ(0, std::memcmp(s.row(y), middle.row(y), middle.rowBytes())) << y;
  const Image stored = readImage((set / "view_0003.png").string());
  int first = -1, last = -1;
  for (int y = 0; y < stored.height; ++y)
    for (int x = 0; x < stored.width; ++x)
      if (stored.row(y)[x * 4 + 3] != 0) {
        if (first < 0) first = y;
        last = y;
        break;
      }
  ASSERT_GE(first, 0);
  const int scanline = (first + last) / 2;
  for (int i = 0; i < 6; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "view_%04d.png", i);
    const Image vi = overBlack(readImage((set / name).string()));
    ASSERT_EQ(0, std::memcmp(s.row(24 + i), vi.row(scanline), vi.rowBytes())) << "EPI row " << i;
  }
}

// A set written with --quilt-only has no view files: the viewer cuts its
// quilt into the views, laid out as the manifest says (a single row from
// the bottom left; a grid's rows from the top), and shows what the set
// with view files shows.
TEST(Viewer, OpensASetWrittenAsAQuiltOnly) {
  if (!haveXvfb()) GTEST_SKIP() << "no xvfb-run";
  struct Case {
    std::string shape, viewName;
    int views;
  };
  for (const Case& c : {Case{"--views 6 --quilt 3x2", "view_%04d.png", 6},
                        Case{"--views 4 --rows 2 --quilt auto", "view_r000_c%04d.png", 4}}) {
    const auto full = test::freshDir("viewer_quilt_full"), only = test::freshDir("viewer_quilt_only");
    ASSERT_TRUE(test::succeeded(test::runMvr("render --size 32x24 " + c.shape + " --out " + full.string())));
    ASSERT_TRUE(
        test::succeeded(test::runMvr("render --size 32x24 " + c.shape + " --quilt-only --out " + only.string())));
    ASSERT_FALSE(std::filesystem::exists(only / "view_0000.png"));
    const std::string shot = (only / "shot.png").string();
    auto r = test::shell("xvfb-run -a " + test::mvrBinary() + " view " + only.string() +
                         " --view 2 --scanline 12 --screenshot " + shot);
    ASSERT_TRUE(test::succeeded(r)) << c.shape;
    const Image s = readImage(shot);
    ASSERT_EQ(s.width, 32);
    ASSERT_EQ(s.height, 24 + c.views);
    auto view = [&](int i) {
      char name[32];
      std::snprintf(name, sizeof name, c.viewName.c_str(), i);
      return overBlack(readImage((full / name).string()));
    };
    const Image shown = view(2);
    for (int y = 0; y < 24; ++y) ASSERT_EQ(0, std::memcmp(s.row(y), shown.row(y), shown.rowBytes())) << c.shape << y;
    for (int i = 0; i < c.views; ++i)
      ASSERT_EQ(0, std::memcmp(s.row(24 + i), view(i).row(12), shown.rowBytes())) << c.shape << " EPI row " << i;
  }
}

TEST(Viewer, StartsOutsideTheSetAreErrors) {
  auto set = test::freshDir("viewer_clamp");
  ASSERT_TRUE(test::succeeded(test::runMvr("render --views 4 --size 32x24 --out " + set.string())));
  for (const char* bad : {"--view 4", "--scanline 24"}) {
    auto r = test::runMvr("view " + set.string() + " " + bad + " --screenshot " + (set / "x.png").string());
    EXPECT_TRUE(test::failed(r)) << bad;
    EXPECT_NE(r.err.find(std::string(bad).substr(0, std::string(bad).find(' '))), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("beyond"), std::string::npos) << r.err;
  }
  auto r = test::runMvr("view " + (set / "view_0000.png").string());
  EXPECT_TRUE(test::failed(r));
}

TEST(Viewer, NotASetIsAnError) {
  auto r = test::runMvr("view /nonexistent/folder_or_scene.json");
  EXPECT_TRUE(test::failed(r));
  EXPECT_EQ(r.err.rfind("mvr: ", 0), 0u) << r.err;
}

}  // namespace
}  // namespace mvr
