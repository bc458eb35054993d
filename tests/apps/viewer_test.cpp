// The viewer under a virtual X display: its screenshot shows the chosen
// view pixel for pixel, and below it the EPI of the chosen scanline.
#include <gtest/gtest.h>

#include <cstring>

#include "mvr/image.h"
#include "mvr/io/compare.h"
#include "mvr/io/image_file.h"
#include "tests/support/cli.h"

namespace mvr {
namespace {

TEST(Viewer, ScreenshotShowsTheViewAndItsEpi) {
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) GTEST_SKIP() << "no xvfb-run";
  auto set = test::freshDir("viewer_set");
  ASSERT_EQ(test::runMvr("render --views 7 --size 64x48 --out " + set.string()).status, 0);
  const std::string shot = (set / "shot.png").string();
  auto r = test::shell("xvfb-run -a " + test::mvrBinary() + " view " + set.string() +
                       " --view 3 --scanline 30 --screenshot " + shot);
  ASSERT_EQ(r.status, 0) << r.err;
  Image s = readImage(shot);
  ASSERT_EQ(s.width, 64);
  ASSERT_EQ(s.height, 48 + 7);
  Image view = readImage((set / "view_0003.png").string());
  for (int y = 0; y < 48; ++y) ASSERT_EQ(0, std::memcmp(s.row(y), view.row(y), view.rowBytes())) << y;
  for (int i = 0; i < 7; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "view_%04d.png", i);
    Image vi = readImage((set / name).string());
    ASSERT_EQ(0, std::memcmp(s.row(48 + i), vi.row(30), vi.rowBytes())) << "EPI row " << i;
  }
}

TEST(Viewer, NotASetIsAnError) {
  auto r = test::runMvr("view /nonexistent/folder_or_scene.json");
  EXPECT_NE(r.status, 0);
  EXPECT_EQ(r.err.rfind("mvr: ", 0), 0u) << r.err;
}

}  // namespace
}  // namespace mvr
