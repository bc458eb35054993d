// mvr live headless (issue 48): the last frame as shown is the native
// image mvr render --native writes of the same scene and quilt (byte for
// byte: the same renderer, camera and mapping); a quilt file is shown as
// it is; under Xvfb a window shows a turning scene as a still render of
// it turned; bad inputs are one-line errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "mvr/images/compare.h"
#include "mvr/images/image_file.h"
#include "tests/support/cli.h"
#include "tests/support/gl_fixture.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;

// A panel of 96 x 64 with a Portrait's lens slope: a few lenses across.
fs::path writeCalibration(const fs::path& dir) {
  fs::create_directories(dir);
  std::ofstream(dir / "visual.json") << R"({"pitch": 52.587, "slope": -7.196, "center": 0.432, "DPI": 20.25,
    "screenW": 96, "screenH": 64, "invView": 1})";
  return dir / "visual.json";
}

const std::string kScene = test::assetsDir() + "/cube.obj";

TEST(Live, HeadlessFrameIsTheNativeImageOfTheRenderedQuilt) {
  const fs::path dir = test::freshDir("live_headless");
  const fs::path calibration = writeCalibration(dir);
  const std::string shot = (dir / "shot.png").string();
  // No display: EGL and an offscreen screen.
  const test::CliResult r = test::shell("env -u DISPLAY " + test::mvrBinary() + " live " + kScene +
                                        " --display 2x2 --size 48x32 --calibration " + calibration.string() +
                                        " --frames 3 --screenshot " + shot + " 1>&2");  // the rate line too
  ASSERT_TRUE(test::succeeded(r));
  EXPECT_TRUE(std::regex_search(r.err, std::regex("mvr: live: 3 frames, [0-9.]+ fps \\(median [0-9.]+ ms, p99 [0-9.]+ ms\\)")))
      << r.err;
  ASSERT_TRUE(test::succeeded(test::runMvr("render " + kScene + " --views 4 --size 48x32 --quilt 2x2 --quilt-only --native " +
                         calibration.string() + " --out " + (dir / "set").string())));
  const Image shown = readImage(shot), native = readImage((dir / "set" / "native_96x64.png").string());
  EXPECT_EQ(shown.width, 96);
  EXPECT_EQ(shown.bytes, native.bytes);
}

// Without a calibration a quilt file is shown as the quilt (scaled to fit
// 1024 pixels: here 1:1).
TEST(Live, QuiltFileIsShownAsItIs) {
  const fs::path dir = test::freshDir("live_quilt");
  fs::create_directories(dir);
  ASSERT_TRUE(test::succeeded(test::runMvr("render " + kScene + " --views 4 --size 48x32 --quilt 2x2 --quilt-only --out " +
                         (dir / "set").string())));
  const std::string quilt = (dir / "set" / "quilt_qs2x2a1.50.png").string(), shot = (dir / "shot.png").string();
  const test::CliResult r = test::shell("env -u DISPLAY " + test::mvrBinary() + " live " + quilt + " --frames 1 --screenshot " + shot);
  ASSERT_TRUE(test::succeeded(r));
  Image q = readImage(quilt);
  const Image shown = readImage(shot);
  ASSERT_EQ(shown.width, q.width);
  ASSERT_EQ(shown.height, q.height);
  for (size_t i = 3; i < q.bytes.size(); i += 4) q.bytes[i] = 255;  // shown opaque: its colour as stored
  EXPECT_EQ(shown.bytes, q.bytes);
}

// A tone map and an exposure reach the live quilt as they reach render's.
TEST(Live, ToneMapsAsRenderDoes) {
  const fs::path dir = test::freshDir("live_tonemap");
  fs::create_directories(dir);
  const std::string look = " --tonemap aces --exposure 1", shot = (dir / "shot.png").string();
  const test::CliResult r = test::shell("env -u DISPLAY " + test::mvrBinary() + " live " + kScene +
                                        " --display 2x2 --size 48x32 --frames 1 --screenshot " + shot + look);
  ASSERT_TRUE(test::succeeded(r)) << r.err;
  ASSERT_TRUE(test::succeeded(test::runMvr("render " + kScene + " --views 4 --size 48x32 --quilt 2x2 --quilt-only" + look +
                                           " --out " + (dir / "set").string())));
  Image q = readImage((dir / "set" / "quilt_qs2x2a1.50.png").string());
  const Image shown = readImage(shot);
  for (size_t i = 3; i < q.bytes.size(); i += 4) q.bytes[i] = 255;
  EXPECT_EQ(shown.bytes, q.bytes);
}

// In a window under Xvfb, a turntable of 90 degrees a second: frame 3 (t =
// 0.1 s) shows the scene turned 9 degrees, as frame 1 of a 10-frame
// render --turntable 90 does.
TEST(Live, WindowShowsTheTurningScene) {
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) GTEST_SKIP() << "no xvfb-run";
  const fs::path dir = test::freshDir("live_window");
  const fs::path calibration = writeCalibration(dir);
  const std::string shot = (dir / "shot.png").string();
  const test::CliResult r = test::shell("xvfb-run -a " + test::mvrBinary() + " live " + kScene +
                                        " --display 2x2 --size 48x32 --calibration " + calibration.string() +
                                        " --turntable 90 --frames 4 --screenshot " + shot);
  ASSERT_TRUE(test::succeeded(r));
  ASSERT_TRUE(test::succeeded(test::runMvr("render " + kScene + " --views 4 --size 48x32 --quilt 2x2 --quilt-only --frames 10 " +
                         "--turntable 90 --native " + calibration.string() + " --out " + (dir / "seq").string())));
  const Image shown = readImage(shot);
  const ImageDifference turned = compareImages(readImage((dir / "seq" / "frame_0001" / "native_96x64.png").string()), shown);
  const ImageDifference still = compareImages(readImage((dir / "seq" / "frame_0000" / "native_96x64.png").string()), shown);
  EXPECT_GE(turned.psnr, 35.0);
  EXPECT_LT(still.psnr, turned.psnr - 5.0);
}

// The GPU path (the renderer in the screen's context, into its texture)
// shows what the CPU path (a render thread, an EPI volume uploaded) does,
// byte for byte, while the scene turns: the GPU spans write the texture's
// layers, the GL modes copy each EPI and svr each view into its layer,
// reading nothing back; the CPU's spans, which hand EPIs on, have them
// uploaded into the layers instead.
TEST(Live, GpuPathShowsWhatTheCpuPathShows) {
  const fs::path dir = test::freshDir("live_paths");
  const fs::path calibration = writeCalibration(dir);
  struct Case {
    std::string backend, said;
  };
  for (const Case& c : {Case{"--pst spans", "into its texture on the GPU, nothing read back"},
                        Case{"--pst strip", "into its texture on the GPU, nothing read back"},
                        Case{"--pst cpu", "read back and uploaded"},
                        Case{"--backend svr", "into its texture on the GPU, nothing read back"}}) {
    std::string shots[2];
    for (int gpu = 0; gpu < 2; ++gpu) {
      shots[gpu] = (dir / ("shot" + std::to_string(gpu) + ".png")).string();
      const test::CliResult r =
          test::shell("env -u DISPLAY " + test::mvrBinary() + " live " + kScene + " " + c.backend +
                      " --display 2x2 --size 48x32 --calibration " + calibration.string() + " --turntable 90 " +
                      "--frames 3 --path " + (gpu ? "gpu" : "cpu") + " --screenshot " + shots[gpu]);
      ASSERT_TRUE(test::succeeded(r)) << c.backend;
      EXPECT_NE(r.err.find(gpu ? c.said : "its own thread"), std::string::npos) << c.backend << ": " << r.err;
    }
    EXPECT_EQ(readImage(shots[1]).bytes, readImage(shots[0]).bytes) << c.backend;
  }
}

TEST(Live, BadInputsAreOneLineErrors) {
  const fs::path dir = test::freshDir("live_bad");
  fs::create_directories(dir);
  std::ofstream(dir / "flat.json") << R"({"pitch": 50, "slope": 0, "center": 0, "DPI": 300, "screenW": 96, "screenH": 64, "invView": 1})";
  struct Case {
    std::string args, message;
  };
  for (const Case& c : {Case{kScene + " --calibration " + (dir / "flat.json").string() + " --frames 1",
                             "flat.json: calibration slope must not be 0"},
                        Case{kScene + " --display 2x2 --frames 1", "--display: a COLSxROWS grid needs --size"},
                        Case{kScene + " --path fast --frames 1", "--path: fast not in {auto,gpu,cpu}"},
                        Case{kScene + " --display 2x2 --size 48x32", "glfw: cannot initialise: no display"}}) {
    const test::CliResult r = test::shell("env -u DISPLAY " + test::mvrBinary() + " live " + c.args);
    EXPECT_TRUE(test::exitedWith(r, 1)) << c.args;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

}  // namespace
}  // namespace mvr
