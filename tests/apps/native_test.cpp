// mvr native and mvr render --native (issue 48), end to end: the GL pass
// and the CPU mapping write the same native image; a sequence writes each
// frame's native image beside its quilt, equal to mvr native of that
// quilt, leaves the frames as a sequence without it renders them, and
// encodes the native video in yuv444p; bad calibrations, a quilt that
// does not divide into its stated tiles and --native without --quilt are
// one-line errors that leave nothing behind.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>

#include "mvr/images/compare.h"
#include "mvr/images/image_file.h"
#include "tests/support/cli.h"
#include "tests/support/video_read.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;

// A small panel (96 x 64) with a Portrait's lens slope and a few lenses
// across: its native image shows every view somewhere.
fs::path writeCalibration(const fs::path& dir) {
  fs::create_directories(dir);
  std::ofstream(dir / "visual.json") << R"({"pitch": {"value": 52.587}, "slope": {"value": -7.196},
    "center": {"value": 0.432}, "DPI": {"value": 20.25}, "screenW": {"value": 96}, "screenH": {"value": 64},
    "invView": {"value": 1}, "flipImageX": {"value": 0}, "flipImageY": {"value": 0}, "flipSubp": {"value": 0},
    "viewCone": {"value": 40}})";
  return dir / "visual.json";
}

const std::string kShape = " --views 4 --size 48x32 --quilt 2x2";

std::string bytesOf(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(Native, GlAndCpuMappingsWriteTheSameImage) {
  const fs::path dir = test::freshDir("native_command");
  const fs::path calibration = writeCalibration(dir);
  ASSERT_TRUE(test::succeeded(test::runMvr("render" + kShape + " --quilt-only --out " + (dir / "set").string())));
  const std::string quilt = (dir / "set" / "quilt_qs2x2a1.50.png").string();
  for (const char* mapping : {"gl", "cpu"}) {
    const test::CliResult r = test::runMvr("native " + quilt + " --calibration " + calibration.string() + " --mapping " +
                                           mapping + " --out " + (dir / (std::string(mapping) + ".png")).string());
    ASSERT_TRUE(test::succeeded(r));
  }
  const Image gl = readImage((dir / "gl.png").string()), cpu = readImage((dir / "cpu.png").string());
  EXPECT_EQ(gl.width, 96);
  EXPECT_EQ(gl.height, 64);
  EXPECT_EQ(gl.bytes, cpu.bytes);
  // Not blank: the scene is in it.
  EXPECT_GT(std::count_if(gl.bytes.begin(), gl.bytes.end(), [](uint8_t b) { return b > 40 && b < 255; }), 1000);
}

// Frames of a turntable with --native and --video: each frame's native
// image is mvr native's of its quilt, its views are those of the same
// sequence without --native (the pass leaves the renderer's GL state as
// it was), and the native video holds every frame at the panel's size in
// full chroma.
TEST(Native, SequenceWritesEachFramesNativeImageAndVideo) {
  const fs::path dir = test::freshDir("native_sequence");
  const fs::path calibration = writeCalibration(dir);
  const std::string frames = " --frames 3 --turntable 60";
  test::CliResult r = test::runMvr("render" + kShape + frames + " --video --native " + calibration.string() +
                                   " --out " + (dir / "with").string());
  ASSERT_TRUE(test::succeeded(r));
  ASSERT_TRUE(test::succeeded(test::runMvr("render" + kShape + frames + " --out " + (dir / "without").string())));
  for (int k = 0; k < 3; ++k) {
    const fs::path frame = dir / "with" / ("frame_000" + std::to_string(k));
    ASSERT_TRUE(fs::exists(frame / "native_96x64.png")) << frame;
    r = test::runMvr("native " + (frame / "quilt_qs2x2a1.50.png").string() + " --calibration " + calibration.string() +
                     " --out " + (dir / "check.png").string());
    ASSERT_TRUE(test::succeeded(r));
    EXPECT_EQ(readImage((frame / "native_96x64.png").string()).bytes, readImage((dir / "check.png").string()).bytes);
    for (int v = 0; v < 4; ++v) {
      const std::string view = "view_000" + std::to_string(v) + ".png";
      EXPECT_EQ(bytesOf(frame / view), bytesOf(dir / "without" / frame.filename() / view)) << frame / view;
    }
  }
  const test::VideoRead video = test::readVideo(dir / "with" / "native_96x64.mp4");
  EXPECT_EQ(video.frames, 3);
  EXPECT_EQ(video.width, 96);
  EXPECT_EQ(video.height, 64);
  EXPECT_EQ(video.format, AV_PIX_FMT_YUV444P);
}

TEST(Native, BadInputsAreOneLineErrors) {
  const fs::path dir = test::freshDir("native_bad");
  const fs::path calibration = writeCalibration(dir);
  ASSERT_TRUE(test::succeeded(test::runMvr("render" + kShape + " --quilt-only --out " + (dir / "set").string())));
  const std::string quilt = (dir / "set" / "quilt_qs2x2a1.50.png").string();
  fs::copy_file(quilt, dir / "odd_qs5x3a1.00.png");
  std::ofstream(dir / "no_dpi.json") << R"({"pitch": 50, "slope": -5, "center": 0, "screenW": 96, "screenH": 64, "invView": 1})";
  struct Case {
    std::string args, message;
  };
  const std::string out = (dir / "native.png").string();
  for (const Case& c : {Case{"native " + quilt + " --calibration " + (dir / "no_dpi.json").string() + " --out " + out,
                             "no_dpi.json: calibration has no DPI"},
                        Case{"native " + (dir / "odd_qs5x3a1.00.png").string() + " --calibration " +
                                 calibration.string() + " --out " + out,
                             "do not divide into 5x3 tiles"},
                        Case{"render" + std::string(" --views 4 --size 48x32") + " --native " + calibration.string() +
                                 " --out " + (dir / "noquilt").string(),
                             "--native: maps the quilt: give --quilt"}}) {
    const test::CliResult r = test::runMvr(c.args);
    EXPECT_TRUE(test::exitedWith(r, 1)) << c.args;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
  EXPECT_FALSE(fs::exists(out));
  EXPECT_FALSE(fs::exists(dir / "noquilt"));
}

}  // namespace
}  // namespace mvr
