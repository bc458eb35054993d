// Sequences from one process (issue 47): `mvr render --frames N
// --turntable DEG`, end to end. Frame 0 is the still render, byte for byte;
// frame k is a still render of the scene turned by DEG k / N (within 40
// dB and 99.5% of pixels within one 8-bit step: the turn is computed in
// double here and in float by the scene file's transform, so a few pixel
// centres near an edge fall the other way); --resume keeps the complete
// frames; bad values are one-line errors that leave nothing behind. The
// quilt video, read back with libavformat and libavcodec, holds every
// frame's quilt at its size, the last one within 30 dB of its PNG (H.264
// at crf 18 and yuv420p's halved chroma on small, hard-edged tiles).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "mvr/images/compare.h"
#include "mvr/images/image_file.h"
#include "tests/support/animated_gltf.h"
#include "tests/support/cli.h"
#include "tests/support/video_read.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;

std::string bytesOf(const fs::path& p) {
  std::stringstream ss;
  ss << std::ifstream(p, std::ios::binary).rdbuf();
  return ss.str();
}

// A tetrahedron of coloured corners whose bounds are centred on the origin
// (the turntable's axis), in a scene with its own camera (the same for
// every frame and for the still renders of the turned scene).
fs::path writeScene(const fs::path& dir, double turnDegrees) {
  fs::create_directories(dir);
  std::ofstream(dir / "tetra.obj") << "v 1 1 1 1 0.2 0.2\nv -1 -1 1 0.2 1 0.2\nv -1 1 -1 0.2 0.2 1\nv 1 -1 -1 1 1 0.2\n"
                                      "f 1 2 3\nf 1 4 2\nf 1 3 4\nf 2 4 3\n";
  const fs::path scene = dir / ("scene_" + std::to_string(int(turnDegrees)) + ".json");
  std::ofstream(scene) << R"({"meshes": [{"file": "tetra.obj", "transform": {"rotate": [)" << turnDegrees
                       << R"(, 0, 1, 0]}}],
    "camera": {"distance": 6, "image_plane": 3.2, "track": [-1, 1], "near": 3, "far": 9}})";
  return scene;
}

const char* const kShape = " --views 4 --size 64x48";

std::string viewFile(const fs::path& set, int v) { return (set / ("view_000" + std::to_string(v) + ".png")).string(); }

// Each of the 4 views of set `frame` is `expected`'s within 40 dB and one
// 8-bit step on 99.5% of pixels; and view v of `a` is visibly not `b`'s
// (< 30 dB), the motion showing.
void expectViewsLike(const fs::path& frame, const fs::path& expected, const fs::path& a, const fs::path& b) {
  for (int v = 0; v < 4; ++v) {
    const ImageDifference d = compareImages(readImage(viewFile(expected, v)), readImage(viewFile(frame, v)));
    EXPECT_GE(d.psnr, 40.0) << viewFile(frame, v);
    EXPECT_GE(d.closeFraction, 0.995) << viewFile(frame, v);
    EXPECT_LT(compareImages(readImage(viewFile(a, v)), readImage(viewFile(b, v))).psnr, 30.0) << viewFile(b, v);
  }
}

// The focal plane moved off the turntable's axis: every frame, not the
// first alone, has the scene moved back by it.
const char* const kFocal = " --focal 0.4";

TEST(Sequence, TurntableFramesAreStillRendersOfTheTurnedScene) {
  const fs::path dir = test::freshDir("sequence_turn");
  const fs::path scene = writeScene(dir, 0);
  const test::CliResult seq =
      test::runMvr("render " + scene.string() + kShape + kFocal + " --frames 3 --turntable 90 --out " + (dir / "seq").string());
  ASSERT_TRUE(test::succeeded(seq));
  const test::CliResult still = test::runMvr("render " + scene.string() + kShape + kFocal + " --out " + (dir / "still").string());
  ASSERT_TRUE(test::succeeded(still));
  for (int v = 0; v < 4; ++v) {
    const std::string view = "view_000" + std::to_string(v) + ".png";
    EXPECT_EQ(bytesOf(dir / "seq" / "frame_0000" / view), bytesOf(dir / "still" / view)) << view;
  }
  // Frame 2 of 3 over 90 degrees: turned by 60.
  const fs::path turned = writeScene(dir, 60);
  const std::string turnedOut = (dir / "turned").string();
  ASSERT_TRUE(test::succeeded(test::runMvr("render " + turned.string() + kShape + kFocal + " --out " + turnedOut)));
  // Not the still: the turn shows.
  expectViewsLike(dir / "seq" / "frame_0002", dir / "turned", dir / "still", dir / "seq" / "frame_0002");
  // Each frame's manifest has its time and turn; sequence.json lists them.
  const auto frame = nlohmann::json::parse(std::ifstream(dir / "seq" / "frame_0001" / "manifest.json"));
  EXPECT_EQ(frame["frame"]["index"], 1);
  EXPECT_DOUBLE_EQ(frame["frame"]["time_s"].get<double>(), 1.0 / 30.0);
  EXPECT_DOUBLE_EQ(frame["frame"]["turntable_deg"].get<double>(), 30.0);
  const auto list = nlohmann::json::parse(std::ifstream(dir / "seq" / "sequence.json"));
  ASSERT_EQ(list["frames"].size(), 3u);
  EXPECT_EQ(list["frames"][2]["dir"], "frame_0002");
  EXPECT_FALSE(fs::exists(dir / "seq" / ".frame_0002.partial"));
}

TEST(Sequence, VideoHoldsEveryQuilt) {
  const fs::path dir = test::freshDir("sequence_video");
  const fs::path scene = writeScene(dir, 0);
  const test::CliResult r = test::runMvr("render " + scene.string() + kShape +
                                         " --frames 5 --turntable 90 --quilt 2x2 --video --out " + (dir / "seq").string());
  ASSERT_TRUE(test::succeeded(r));
  const fs::path mp4 = dir / "seq" / "quilt_qs2x2a1.33.mp4";
  ASSERT_TRUE(fs::exists(mp4));
  EXPECT_FALSE(fs::exists(dir / "seq" / "quilt_qs2x2a1.33.mp4.part"));
  const test::VideoRead v = test::readVideo(mp4);
  EXPECT_EQ(v.codec, AV_CODEC_ID_H264);
  EXPECT_EQ(v.format, AV_PIX_FMT_YUV420P);
  EXPECT_EQ(v.frames, 5);
  EXPECT_EQ(v.width, 128);
  EXPECT_EQ(v.height, 96);
  const Image quilt = readImage((dir / "seq" / "frame_0004" / "quilt_qs2x2a1.33.png").string());
  ASSERT_EQ(v.last.width, quilt.width);
  const ImageDifference d = compareImages(quilt, v.last);
  EXPECT_GE(d.psnr, 30.0);
  std::printf("video's last frame against its quilt: %.2f dB\n", d.psnr);
}

TEST(Sequence, ResumeKeepsTheCompleteFrames) {
  const fs::path dir = test::freshDir("sequence_resume");
  const fs::path scene = writeScene(dir, 0);
  const std::string args = "render " + scene.string() + kShape + " --time 0:0.1 --turntable 45 --quilt 2x2 --video --out " +
                           (dir / "seq").string();
  ASSERT_TRUE(test::succeeded(test::runMvr(args)));  // [0, 0.1) at 30 frames/s: 3 frames
  ASSERT_TRUE(fs::exists(dir / "seq" / "frame_0002" / "manifest.json"));
  EXPECT_FALSE(fs::exists(dir / "seq" / "frame_0003"));
  const std::string frame1 = bytesOf(dir / "seq" / "frame_0001" / "view_0002.png");
  // An interrupted run: frame 1 missing, frame 2 half-written.
  fs::remove_all(dir / "seq" / "frame_0001");
  fs::rename(dir / "seq" / "frame_0002", dir / "seq" / ".frame_0002.partial");
  const fs::file_time_type kept = fs::last_write_time(dir / "seq" / "frame_0000" / "view_0000.png");
  const test::CliResult again = test::shell(test::mvrBinary() + " " + args + " --resume >/dev/null");
  ASSERT_TRUE(test::succeeded(again));
  EXPECT_NE(again.err.find("rendered 2 of 3 frames"), std::string::npos) << again.err;
  EXPECT_EQ(fs::last_write_time(dir / "seq" / "frame_0000" / "view_0000.png"), kept);
  EXPECT_EQ(bytesOf(dir / "seq" / "frame_0001" / "view_0002.png"), frame1);
  EXPECT_TRUE(fs::exists(dir / "seq" / "frame_0002" / "manifest.json"));
  EXPECT_FALSE(fs::exists(dir / "seq" / ".frame_0002.partial"));
  EXPECT_EQ(test::readVideo(dir / "seq" / "quilt_qs2x2a1.33.mp4").frames, 3);  // the kept frame's quilt read back
}

// An animated glTF without --frames: its animation's length at --fps 2
// (t = 0, 0.5, 1, 1.5 of [0, 2)); frame 3 is a still render of the file
// posed at 1.5 by hand, through a scene file with its own camera.
using GltfWriter = std::string (*)(const fs::path&, bool, double);
void expectFramesArePosedStills(const fs::path& dir, GltfWriter write, const std::string& clip,
                                const std::string& flags = "") {
  fs::create_directories(dir);
  write(dir / "anim.gltf", true, 0.0);
  write(dir / "posed.gltf", false, 1.5);
  const char* camera = R"("camera": {"distance": 8, "image_plane": 5, "track": [-1, 1], "near": 4, "far": 12})";
  std::ofstream(dir / "anim.json") << R"({"meshes": [{"file": "anim.gltf"}], )" << camera << "}";
  std::ofstream(dir / "posed.json") << R"({"meshes": [{"file": "posed.gltf"}], )" << camera << "}";
  const std::string clipFlag = clip.empty() ? "" : " --clip " + clip;
  const test::CliResult r = test::runMvr("render " + (dir / "anim.json").string() + kShape + flags + " --fps 2" + clipFlag +
                                         " --out " + (dir / "seq").string());
  ASSERT_TRUE(test::succeeded(r));
  EXPECT_TRUE(fs::exists(dir / "seq" / "frame_0003" / "manifest.json"));
  EXPECT_FALSE(fs::exists(dir / "seq" / "frame_0004"));
  ASSERT_TRUE(test::succeeded(test::runMvr("render " + (dir / "posed.json").string() + kShape + flags + " --out " + (dir / "posed").string())));
  // Frame 0 is the rest pose: the animation shows.
  expectViewsLike(dir / "seq" / "frame_0003", dir / "posed", dir / "posed", dir / "seq" / "frame_0000");
}

TEST(Sequence, AnimationFramesAreStillRendersOfThePosedFile) {
  const fs::path dir = test::freshDir("sequence_trs");
  expectFramesArePosedStills(dir, test::writeAnimatedGltf, "Walk");
  const test::CliResult missing =
      test::runMvr("render " + (dir / "anim.json").string() + kShape + " --clip Run --out " + (dir / "run").string());
  EXPECT_TRUE(test::exitedWith(missing, 1));
  EXPECT_NE(missing.err.find("--clip: the scene has no animation clip named 'Run'"), std::string::npos) << missing.err;
  EXPECT_FALSE(fs::exists(dir / "run"));
}

TEST(Sequence, MorphFramesAreStillRendersOfThePosedFile) {
  expectFramesArePosedStills(test::freshDir("sequence_morph"), test::writeMorphGltf, "");
}

TEST(Sequence, SkinFramesAreStillRendersOfThePosedFile) {
  expectFramesArePosedStills(test::freshDir("sequence_skin"), test::writeSkinnedGltf, "Bend");
  // With the focal plane off the scene's centre, the skin posed behind it too.
  expectFramesArePosedStills(test::freshDir("sequence_skin_focal"), test::writeSkinnedGltf, "Bend", " --focal 0.3");
}

// A bare animated glTF (no camera of its own) is framed on every pose of
// its clip: the tetrahedron walks 1.5 to the right and grows 1.5 times by
// t = 1.5, and stays inside every view of every frame, clear of the edges.
// Framed on frame 0 alone it walked out (its last frame cut at the right).
TEST(Sequence, ABareClipIsFramedOnEveryPose) {
  const fs::path dir = test::freshDir("sequence_framed");
  fs::create_directories(dir);
  test::writeAnimatedGltf(dir / "walk.gltf", true);
  const test::CliResult r =
      test::runMvr("render " + (dir / "walk.gltf").string() + kShape + " --fps 2 --out " + (dir / "seq").string());
  ASSERT_TRUE(test::succeeded(r));
  for (int k = 0; k < 4; ++k)
    for (int v = 0; v < 4; ++v) {
      const Image view = readImage(viewFile(dir / "seq" / ("frame_000" + std::to_string(k)), v));
      long covered = 0, onEdge = 0;
      for (int y = 0; y < view.height; ++y)
        for (int x = 0; x < view.width; ++x) {
          const bool in = view.row(y)[x * 4 + 3] != 0;
          covered += in;
          onEdge += in && (x == 0 || y == 0 || x == view.width - 1 || y == view.height - 1);
        }
      EXPECT_GT(covered, 20) << "frame " << k << " view " << v;
      EXPECT_EQ(onEdge, 0) << "frame " << k << " view " << v;
    }
}

// A still at a time of the clip is framed on every pose too, as the
// sequence is: frame 2 of --fps 2 (t = 1) is byte for byte the still
// --frames 1 --time 1 renders, and so is frame 0 of a sequence that
// starts there (framed on the clip, not on its own range). Framed on
// their own poses, the three differed.
TEST(Sequence, AStillAtATimeIsFramedAsTheSequence) {
  const fs::path dir = test::freshDir("sequence_still_framed");
  fs::create_directories(dir);
  test::writeAnimatedGltf(dir / "walk.gltf", true);
  const std::string scene = "render " + (dir / "walk.gltf").string() + kShape;
  ASSERT_TRUE(test::succeeded(test::runMvr(scene + " --fps 2 --out " + (dir / "seq").string())));
  ASSERT_TRUE(test::succeeded(test::runMvr(scene + " --frames 1 --time 1 --out " + (dir / "still").string())));
  ASSERT_TRUE(test::succeeded(test::runMvr(scene + " --time 1:1.5 --fps 2 --out " + (dir / "late").string())));
  for (int v = 0; v < 4; ++v) {
    const Image frame = readImage(viewFile(dir / "seq" / "frame_0002", v));
    EXPECT_EQ(frame.bytes, readImage(viewFile(dir / "still" / "frame_0000", v)).bytes) << "view " << v;
    EXPECT_EQ(frame.bytes, readImage(viewFile(dir / "late" / "frame_0000", v)).bytes) << "view " << v;
  }
}

TEST(Sequence, BadValuesAreOneLineErrors) {
  const fs::path dir = test::freshDir("sequence_bad");
  const fs::path scene = writeScene(dir, 0);
  const fs::path out = dir / "out";
  struct Case {
    const char* args;
    const char* message;
  };
  for (const Case& c : {Case{"--frames 0", "--frames: must be 1 to 1000000"},
                        Case{"--frames 2 --fps -1", "--fps: must be a positive number"},
                        Case{"--time 3:1", "--time: the end B must come after the start A"},
                        Case{"--time x", "--time: 'x' is not a number"},
                        Case{"--turntable 90", "--turntable: needs a sequence: --frames N or --time A:B"},
                        Case{"--frames 2 --resume --stream -", "--resume: keeps complete frame folders: not with a stream"},
                        Case{"--frames 2 --quilt 2x2 --video --stream -", "--video: encodes image sets' quilts: not with a stream"},
                        Case{"--frames 2 --video", "--video: encodes the quilts: give --quilt"},
                        Case{"--quilt 2x2 --video", "--video: needs a sequence"},
                        Case{"--frames 2 --quilt 2x2 --video --crf 60", "--crf: must be 0 to 51"}}) {
    const test::CliResult r = test::runMvr("render " + scene.string() + kShape + " " + c.args + " --out " + out.string());
    EXPECT_TRUE(test::exitedWith(r, 1)) << c.args;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << ": " << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << c.args << ": " << r.err;
    EXPECT_FALSE(fs::exists(out)) << c.args;
  }
}

}  // namespace
}  // namespace mvr
