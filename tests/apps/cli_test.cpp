// The `mvr` program end to end, as a user runs it.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <nlohmann/json.hpp>

#include "mvr/io/compare.h"
#include "mvr/io/image_file.h"
#include "mvr/io/manifest.h"
#include "tests/support/asset_scene.h"
#include "tests/support/cli.h"
#include "tests/support/gl_fixture.h"

namespace {

namespace test = mvr::test;

namespace fs = std::filesystem;

struct Result {
  int status;
  std::string err;
};

Result run(const std::string& args) {
  // ctest runs tests in parallel processes: one stderr file per process.
  const fs::path errFile =
      fs::temp_directory_path() / ("mvr_cli_stderr_" + std::to_string(getpid()) + ".txt");
  const std::string cmd = test::mvrBinary() + " " + args + " >/dev/null 2>" + errFile.string();
  int rc = std::system(cmd.c_str());
  std::stringstream ss;
  ss << std::ifstream(errFile).rdbuf();
  return {WEXITSTATUS(rc), ss.str()};
}

fs::path outDir(const std::string& name) {
  fs::path d = fs::temp_directory_path() / ("mvr_cli_" + name);
  fs::remove_all(d);
  return d;
}

void expectSet(const fs::path& dir, int views, const std::string& backend) {
  for (int i = 0; i < views; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "view_%04d.png", i);
    EXPECT_TRUE(fs::exists(dir / name)) << dir / name;
  }
  ASSERT_TRUE(fs::exists(dir / "manifest.json"));
  auto m = nlohmann::json::parse(std::ifstream(dir / "manifest.json"));
  EXPECT_EQ(m["backend"], backend);
  EXPECT_EQ(m["views"], views);
  EXPECT_TRUE(m["timings_s"].contains("total"));
}

TEST(Cli, RendersDefaultSceneUnderEgl) {
  fs::path d = outDir("egl");
  Result r = run("render --gl egl --views 4 --size 48x36 --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.err;
  expectSet(d, 4, "mvr");
}

TEST(Cli, RendersDefaultSceneUnderOsMesa) {
  fs::path d = outDir("osmesa");
  Result r = run("render --gl osmesa --views 3 --size 40x30 --out " + d.string());
  // A GPU host runs the suite with GL forced to EGL (scripts/gpu-tests) and
  // has no OSMesa; everywhere else its absence is a failure.
  const char* forced = std::getenv("MVR_TEST_GL");
  if (r.status != 0 && forced && std::string(forced) == "egl" && r.err.find("libOSMesa") != std::string::npos)
    GTEST_SKIP() << r.err;
  ASSERT_EQ(r.status, 0) << r.err;
  expectSet(d, 3, "mvr");
}

TEST(Cli, EveryBaselineWritesItsSet) {
  for (std::string b : {"svr-layered", "deferred"}) {
    fs::path d = outDir(b);
    Result r = run("render --backend " + b + " --views 3 --size 40x30 --out " + d.string());
    ASSERT_EQ(r.status, 0) << r.err;
    expectSet(d, 3, b);
  }
}

TEST(Cli, CompareReportsIdenticalAndRejectsMismatch) {
  fs::path a = outDir("cmp_a"), b = outDir("cmp_b"), c = outDir("cmp_c");
  ASSERT_EQ(run("render --views 2 --size 40x30 --out " + a.string()).status, 0);
  ASSERT_EQ(run("render --views 2 --size 40x30 --out " + b.string()).status, 0);
  ASSERT_EQ(run("render --views 2 --size 42x30 --out " + c.string()).status, 0);
  EXPECT_EQ(run("compare " + a.string() + " " + b.string()).status, 0);
  Result mismatch = run("compare " + a.string() + " " + c.string());
  EXPECT_NE(mismatch.status, 0);
  EXPECT_NE(mismatch.err.find("size mismatch"), std::string::npos) << mismatch.err;
}

TEST(Cli, BadInputGivesOneLineErrorAndNoSet) {
  fs::path d = outDir("bad");
  const fs::path noTexture = outDir("bad_scene") / "missing_texture.json";
  fs::create_directories(noTexture.parent_path());
  std::ofstream(noTexture) << R"({"meshes": [{"file": ")" << test::assetsDir()
                           << R"(/plane.obj", "material": {"texture": "nothere.png"}}]})";
  // A square image is neither a cube strip (6:1) nor a sphere map pair (2:1).
  const fs::path squareMap = noTexture.parent_path() / "square_map.json";
  std::ofstream(squareMap) << R"({"meshes": [{"file": ")" << test::assetsDir()
                           << R"(/plane.obj", "material": {"reflection_map": ")" << test::assetsDir()
                           << R"(/checker.png"}}]})";
  for (std::string args : std::vector<std::string>{"render /nonexistent/scene.json --out " + d.string(),
                           "render " + noTexture.string() + " --out " + d.string(),
                           "render " + squareMap.string() + " --backend mvr --pst cpu --out " + d.string(),
                           "render " + squareMap.string() + " --backend deferred --out " + d.string(),
                           "render --texture nope --out " + d.string(),
                           "render --backend svr --texture direct --out " + d.string(),
                           "render --backend interp --acquire nope --out " + d.string(),
                           "render --backend interp --max-layers 0 --out " + d.string(),
                           "render --backend mvr --acquire center --out " + d.string(),
                           "render --backend interp --coalesce -1 --out " + d.string(),
                           "render --backend interp --coalesce wide --out " + d.string(),
                           "render --backend svr --coalesce 1 --out " + d.string(),
                           "render --backend interp --budget 1 --out " + d.string(),
                           "render --backend interp --splits -2 --out " + d.string(),
                           "render --backend interp --overlap -1 --out " + d.string(),
                           "render --backend mvr --splits 2 --out " + d.string(),
                           "render --backend interp --blend soft --out " + d.string(),
                           "render --backend svr --blend track --out " + d.string(),
                           "render --backend deferred --visibility --out " + d.string(),
                           "render --backend mvr --layer-passes --out " + d.string(),
                           "render --views 0 --out " + d.string(),
                           "render --size 10 --out " + d.string(),
                           "render --backend nope --out " + d.string(),
                           "render --gl vulkan --out " + d.string(),
                           // 4 TiB of views: in a quilt, in memory, refused; to reorder, more
                           // than the scratch disk holds; a budget below one frame.
                           "render --views 65536 --size 4096x4096 --quilt auto --out " + d.string(),
                           "render --views 65536 --size 4096x4096 --memory 1G --threads 1 --out " + d.string(),
                           "render --views 8 --size 4096x4096 --memory 100M --out " + d.string(),
                           "render --memory 12X --out " + d.string(),
                           "render --depth --order epi --out " + d.string(),
                           "render --depth --stream " + (d / "s.epis").string(),
                           "render --backend svr --tau 0.1 --out " + d.string(),
                           "render --backend warp --acquire center --out " + d.string(),
                           "render --backend svr --warp-path cpu --out " + d.string(),
                           "render --backend warp --warp-path fast --out " + d.string(),
                           "synthesize --out " + d.string(),
                           "synthesize --from /nonexistent --out " + d.string(),
                           "synthesize --from " + test::assetsDir() + " --tau 2 --out " + d.string(),
                           "synthesize --from " + test::assetsDir() + " --warp-path fast --out " + d.string(),
                           "frobnicate"}) {
    Result r = run(args);
    EXPECT_NE(r.status, 0) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_EQ(r.err.rfind("mvr: ", 0), 0u) << r.err;
    EXPECT_FALSE(fs::exists(d / "manifest.json")) << args;
    // The message each case must name (gtest's EXPECT is an if/else: no
    // bare EXPECT under an if).
    const std::pair<std::string, std::string> named[] = {
        {noTexture.string(), "nothere.png"},
        {squareMap.string(), "checker.png: a reflection map must be"},
        {"--quilt auto", "GiB for the quilt) but"},
        {"--memory 1G", "the scratch file needs 4096.0 GiB but the disk has"},
        {"--memory 100M", "mvr: --memory: 100.0 MiB cannot hold one frame (64.0 MiB)"},
        {"12X", "mvr: --memory: '12X' is not a size"}};
    for (const auto& [marker, message] : named) {
      if (args.find(marker) == std::string::npos) continue;
      EXPECT_NE(r.err.find(message), std::string::npos) << r.err;
    }
  }
}

// Each format stores what was asked for, the manifest says so, and an
// encoding the format cannot store is one line naming the option.
TEST(Cli, EncodingsEveryFormatOffers) {
  struct Case {
    std::string flags, file;
    int bits;
    std::string codec;
  };
  for (const Case& c : {Case{"--format exr", "view_0000.exr", 32, "zip"},
                        Case{"--format exr --bits 16 --codec piz", "view_0000.exr", 16, "piz"},
                        Case{"--format tiff --codec lzw", "view_0000.tiff", 8, "lzw"},
                        Case{"--format tiff --bits 16 --codec none", "view_0000.tiff", 16, "none"},
                        Case{"--bits 16", "view_0000.png", 16, ""}}) {
    const fs::path d = outDir("encoding");
    const Result r = run("render --views 2 --size 32x24 " + c.flags + " --out " + d.string());
    ASSERT_EQ(r.status, 0) << c.flags << ": " << r.err;
    const mvr::ImageEncoding e = mvr::readImageEncoding((d / c.file).string());
    EXPECT_EQ(e.bits, c.bits) << c.flags;
    EXPECT_EQ(e.codec, c.codec) << c.flags;
    const mvr::Manifest m = mvr::Manifest::read(d.string());
    EXPECT_EQ(m.bits, c.bits) << c.flags;
    EXPECT_EQ(m.codec, c.codec) << c.flags;
    fs::remove_all(d);
  }
  for (const std::string flags : {"--format exr --bits 8", "--format png --bits 32", "--format png --codec zip",
                                  "--format tiff --codec piz"}) {
    const fs::path d = outDir("encoding_bad");
    const Result r = run("render --views 2 --size 32x24 " + flags + " --out " + d.string());
    EXPECT_NE(r.status, 0) << flags;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << flags << ": " << r.err;
    EXPECT_NE(r.err.find(flags.find("codec") != std::string::npos ? "--codec" : "--bits"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(d / "manifest.json")) << flags;
  }
}

TEST(Cli, DroppedFacesWarnAndStrictRefuses) {
  const fs::path d = outDir("dropped");
  const fs::path ply = outDir("dropped_scene") / "bad_index.ply";
  fs::create_directories(ply.parent_path());
  std::ofstream(ply) << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                        "property float z\nelement face 3\nproperty list uchar int vertex_indices\nend_header\n"
                        "0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n3 0 1 7\n";
  const std::string args = "render " + ply.string() + " --views 2 --size 32x24 --out " + d.string();
  Result r = run(args);
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("mvr: warning: " + ply.string() + ": 1 faces dropped"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(d / "manifest.json"));
  fs::remove_all(d);
  r = run(args + " --strict");
  EXPECT_NE(r.status, 0);
  EXPECT_EQ(r.err, "mvr: " + ply.string() +
                       ": 1 faces dropped (a repeated corner or a vertex that does not exist) (--strict)\n");
  EXPECT_FALSE(fs::exists(d / "manifest.json"));
}

// A file-size limit (as a full disk would) fails the write: one line naming
// the file and the system's reason, non-zero status, and no set left that
// looks complete (before, truncated PNGs and a manifest were committed).
TEST(Cli, FailedWritesLeaveNoSet) {
  const fs::path d = outDir("efbig");
  const fs::path stream = outDir("efbig_stream") / "s.bin";
  fs::create_directories(stream.parent_path());
  for (const std::string& args : {"render --views 4 --size 320x240 --out " + d.string(),
                                  "render --views 4 --size 320x240 --format exr --out " + d.string(),
                                  "stream --views 4 --size 320x240 --to " + stream.string()}) {
    const test::CliResult r = test::shell("ulimit -f 16; " + test::mvrBinary() + " " + args + " >/dev/null");
    EXPECT_NE(r.status, 0) << args;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << ": " << r.err;
    EXPECT_NE(r.err.find(args.rfind("render", 0) == 0 ? ": cannot write: File too large"
                                                        : "s.bin: cannot write stream: File too large"),
              std::string::npos)
        << r.err;
    EXPECT_FALSE(fs::exists(d / "manifest.json")) << args;
    EXPECT_TRUE(!fs::exists(d) || fs::is_empty(d)) << args << ": files left behind";
    EXPECT_FALSE(fs::exists(stream)) << args;
  }
}

// OpenImageIO is a module loaded at run time; without it a render that
// writes images fails in one line naming the module, and leaves no set.
// OpenImageIO's module writes EXR and TIFF (PNGs are our own encoder's):
// without it a PNG set is written, an EXR set is a one-line error.
TEST(Cli, MissingImageModuleIsOneLineError) {
  const fs::path d = outDir("no_codec");
  const std::string noModule = "MVR_IMAGE_CODEC=/nonexistent/libmvr_oiio.so " + test::mvrBinary();
  test::CliResult r = test::shell(noModule + " render --views 2 --size 16x12 --out " + d.string() + " >/dev/null");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(mvr::readImage((d / "view_0001.png").string()).width, 16);
  r = test::shell(noModule + " render --views 2 --size 16x12 --format exr --out " + d.string() + " >/dev/null");
  EXPECT_NE(r.status, 0);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("mvr: /nonexistent/libmvr_oiio.so: cannot load the image codec module"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(d / "manifest.json"));
}

TEST(Cli, RendersUnderGlfwWithAVirtualDisplay) {
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) GTEST_SKIP() << "no xvfb-run";
  fs::path d = outDir("glfw");
  const std::string cmd = "xvfb-run -a " + test::mvrBinary() +
                          " render --gl glfw --views 2 --size 32x24 --out " + d.string() +
                          " >/dev/null 2>&1";
  ASSERT_EQ(WEXITSTATUS(std::system(cmd.c_str())), 0);
  expectSet(d, 2, "mvr");
  auto m = nlohmann::json::parse(std::ifstream(d / "manifest.json"));
  EXPECT_EQ(m["gl"]["platform"], "glfw");
}

TEST(Cli, MvrWritesEpisAndStats) {
  fs::path d = outDir("epis");
  Result r = run("render --backend mvr --pst cpu --order epi --views 5 --size 40x30 --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(d / "epi_0000.png"));
  EXPECT_TRUE(fs::exists(d / "epi_0029.png"));
  auto m = nlohmann::json::parse(std::ifstream(d / "manifest.json"));
  EXPECT_GT(m["counters"]["slices"].get<double>(), 0);
  EXPECT_GT(m["counters"]["slice_table_bytes"].get<double>(), 0);
  for (const char* stage : {"transform", "slicing", "raster"})
    EXPECT_TRUE(m["timings_s"].contains(stage)) << stage;
  // Start-up, phase by phase; the phases lie within all of it (the scene
  // loads while GL starts, then the renderer is made).
  const nlohmann::json& startup = m["startup_s"];
  for (const char* phase : {"scene", "gl", "renderer"}) {
    ASSERT_TRUE(startup.contains(phase)) << phase;
    EXPECT_GE(startup[phase].get<double>(), 0.0) << phase;
  }
  EXPECT_LE(std::max(startup["scene"].get<double>(), startup["gl"].get<double>()) + startup["renderer"].get<double>(),
            startup["before_render"].get<double>());
  // PNGs are written without OpenImageIO: its module never loaded.
  EXPECT_FALSE(startup.contains("image_module_load"));
  EXPECT_EQ(m["cameras"]["views"].size(), 5u);
  // An exr set needs the module, and says how long its load took.
  r = run("render --backend mvr --pst cpu --format exr --views 2 --size 16x12 --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.err;
  m = nlohmann::json::parse(std::ifstream(d / "manifest.json"));
  EXPECT_GT(m["startup_s"]["image_module_load"].get<double>(), 0.0);
}

// With no --pst, mvr and interp take the CPU spans where GL renders on the
// CPU (exact, and several times the GL modes' speed there), and on a GPU
// the GPU spans where they shade the scene, else their GL defaults; a
// named mode, texture mode or PST builder is kept.
TEST(Cli, TheDefaultAccuracyModeFollowsWhereGlRenders) {
  const fs::path d = outDir("default_pst");
  auto pstOf = [&](const std::string& args) {
    const Result r = run("render " + args + " --views 3 --size 40x30 --out " + d.string());
    EXPECT_EQ(r.status, 0) << r.err;
    const auto m = nlohmann::json::parse(std::ifstream(d / "manifest.json"));
    const std::string renderer = m["gl"]["renderer"];
    return std::pair{m["pst"].get<std::string>(), renderer.find("llvmpipe") != std::string::npos};
  };
  const auto [mvr, onCpu] = pstOf("--backend mvr");  // the bundled scene is diffuse
  EXPECT_EQ(mvr, onCpu ? "cpu" : "spans");
  EXPECT_EQ(pstOf("--backend interp").first, onCpu ? "cpu" : "spans");
  const std::string shiny = test::assetPath("shiny.json");
  EXPECT_EQ(pstOf(shiny + " --backend mvr").first, onCpu ? "cpu" : "strip");
  EXPECT_EQ(pstOf(shiny + " --backend interp").first, onCpu ? "cpu" : "spans");
  EXPECT_EQ(pstOf(shiny + " --backend interp --splits 2").first, onCpu ? "cpu" : "quad");
  EXPECT_EQ(pstOf("--backend mvr --pst strip").first, "strip");
  EXPECT_EQ(pstOf("--backend mvr --pst-builder cpu").first, "strip");
  EXPECT_EQ(pstOf("--backend mvr --texture direct").first, "strip");
  EXPECT_EQ(pstOf("--backend interp --pst exact").first, "exact");
}

// --depth: a float exr beside every view of a grid, 0 exactly where the
// view is empty, the same surfaces as svr's depth (mvr's CPU spans are
// exact), and the manifest says what the files hold. Where a pixel centre
// lies within the GL's sub-pixel snapping of an edge between two surfaces,
// the fill rule may give it either (render_helpers.h: well under 0.5% of
// pixels; 0.23% on an NVIDIA H100, none on llvmpipe).
TEST(Cli, DepthMapsBesideEveryView) {
  const fs::path mvr = outDir("depth_mvr"), svr = outDir("depth_svr");
  const std::string common = " --views 3 --rows 2 --size 40x30 --depth --out ";
  Result r = run("render --backend mvr --pst cpu" + common + mvr.string());
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("render --backend svr" + common + svr.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto m = nlohmann::json::parse(std::ifstream(mvr / "manifest.json"));
  EXPECT_EQ(m["depth"]["files"], "depth_r%03d_c%04d.exr");
  EXPECT_EQ(m["depth"]["channel"], "Z");
  EXPECT_EQ(m["files"], 12);  // 6 views, 6 depth maps
  size_t covered = 0, agree = 0;
  for (int row = 0; row < 2; ++row)
    for (int view = 0; view < 3; ++view) {
      char name[40];
      std::snprintf(name, sizeof name, "r%03d_c%04d", row, view);
      const mvr::Image color = mvr::readImage((mvr / ("view_" + std::string(name) + ".png")).string());
      const mvr::DepthImage depth = mvr::readDepthImage((mvr / ("depth_" + std::string(name) + ".exr")).string());
      const mvr::DepthImage reference =
          mvr::readDepthImage((svr / ("depth_" + std::string(name) + ".exr")).string());
      ASSERT_EQ(depth.width, 40);
      ASSERT_EQ(depth.height, 30);
      for (int y = 0; y < 30; ++y)
        for (int x = 0; x < 40; ++x) {
          const bool seen = color.pixel(x, y).a > 0.5f;
          EXPECT_EQ(seen, depth.at(x, y) > 0.0f) << name << " " << x << "," << y;
          if (!seen || reference.at(x, y) == 0.0f) continue;
          ++covered;
          agree += std::abs(depth.at(x, y) - reference.at(x, y)) < 1e-3f;
        }
    }
  EXPECT_GT(covered, 1000u);
  EXPECT_GE(double(agree) / double(covered), 0.995);
}

// The warp back end by GL and on the CPU from the command line: the same
// views within what the GL grid's merged cells move (measured: 42.9 dB
// at the worst view, 64.5 at the references).
TEST(Cli, WarpsByGlAndOnTheCpu) {
  const fs::path gl = outDir("warp_gl"), cpu = outDir("warp_cpu");
  for (const auto& [path, dir] : {std::pair{"gl", gl}, std::pair{"cpu", cpu}}) {
    const Result r = run(std::string("render --backend warp --warp-path ") + path +
                         " --views 5 --size 96x72 --out " + dir.string());
    ASSERT_EQ(r.status, 0) << r.err;
    expectSet(dir, 5, "warp");
  }
  for (int view = 0; view < 5; ++view) {
    char name[32];
    std::snprintf(name, sizeof name, "view_%04d.png", view);
    const mvr::ImageDifference diff =
        mvr::compareImages(mvr::readImage((gl / name).string()), mvr::readImage((cpu / name).string()));
    EXPECT_GE(diff.psnr, 40.0) << name;
  }
}

// RGB-D out, then in: three svr views with depth, synthesized into nine
// views and a quilt by the warp back end; the views at the references are
// the references, those between close to svr's.
TEST(Cli, SynthesizesATrackFromRgbdReferences) {
  const fs::path refs = outDir("syn_refs"), out = outDir("syn_out"), svr = outDir("syn_svr");
  Result r = run("render --backend svr --views 3 --size 128x96 --depth --out " + refs.string());
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("synthesize --from " + refs.string() + " --views 9 --quilt auto --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  r = run("render --backend svr --views 9 --size 128x96 --out " + svr.string());
  ASSERT_EQ(r.status, 0) << r.err;
  expectSet(out, 9, "warp");
  const auto m = nlohmann::json::parse(std::ifstream(out / "manifest.json"));
  EXPECT_EQ(m["references"]["layout"], "mvr");
  EXPECT_EQ(m["references"]["count"], 3);
  EXPECT_EQ(m["width"], 128);  // the references' size by default
  EXPECT_TRUE(fs::exists(out / m["quilt"].get<std::string>()));
  for (int view = 0; view < 9; ++view) {
    char name[32];
    std::snprintf(name, sizeof name, "view_%04d.png", view);
    const mvr::ImageDifference diff =
        mvr::compareImages(mvr::readImage((svr / name).string()), mvr::readImage((out / name).string()));
    if (view % 4 == 0) {
      EXPECT_GE(diff.closeFraction, 0.999) << name;  // a reference
    }
    EXPECT_GE(diff.psnr, 26.0) << name;  // 8-bit references: 28.3 dB measured at the worst view
  }
}

// A display user's camera from the command line (issue 19): a quad at
// z = 0.5, its centre put on the display plane (--focal center), a 40
// degree cone, an opaque grey background. On the display plane the quad
// has no disparity: every view is the same image. The manifest gives the
// cone and the plane, and V in the mesh's own coordinates.
TEST(Cli, CameraInDisplayTerms) {
  const fs::path d = outDir("display_camera"), mesh = outDir("display_mesh") / "quad.obj";
  fs::create_directories(mesh.parent_path());
  std::ofstream(mesh) << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3\nf 1 3 4\n";
  // A scene file, as a bare mesh is centred on load.
  const fs::path scene = mesh.parent_path() / "quad.json";
  std::ofstream(scene) << R"({"meshes": [{"file": "quad.obj", "transform": {"translate": [0, 0, 0.5]}}]})";
  Result r = run("render " + scene.string() + " --backend mvr --pst cpu --views 5 --size 48x36 --cone 40 "
                 "--focal center --background 0.25,0.25,0.25 --opaque --quilt auto --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto m = nlohmann::json::parse(std::ifstream(d / "manifest.json"));
  EXPECT_NEAR(m["camera"]["cone_deg"].get<double>(), 40.0, 1e-9);
  EXPECT_NEAR(m["camera"]["image_plane_z"].get<double>(), 0.5, 1e-7);
  EXPECT_EQ(m["background"][3], 1.0);
  // V takes the quad's centre to the camera's axis at the camera distance.
  const nlohmann::json& v = m["cameras"]["views"][2]["V"];
  EXPECT_NEAR(v[2][0].get<double>() * 0 + v[2][2].get<double>() * 0.5 + v[2][3].get<double>(),
              m["camera"]["distance"].get<double>(), 1e-6);
  EXPECT_NEAR(m["cameras"]["views"][2]["eye"][2].get<double>(), 0.5 + m["camera"]["distance"].get<double>(), 1e-6);
  const mvr::Image first = mvr::readImage((d / "view_0000.png").string());
  for (int view = 1; view < 5; ++view) {
    char name[32];
    std::snprintf(name, sizeof name, "view_%04d.png", view);
    const mvr::ImageDifference diff = mvr::compareImages(first, mvr::readImage((d / name).string()));
    EXPECT_GE(diff.closeFraction, 0.995) << name;  // no disparity, up to edge pixels
  }
  // Opaque: the background where the quad is not, alpha 1 everywhere.
  const glm::vec4 corner = first.linear(0, 0);
  EXPECT_NEAR(corner.r, 0.25f, 0.01f);
  EXPECT_EQ(corner.a, 1.0f);
  // The field of view sizes the image plane; depthiness scales the track:
  // a 40 degree cone twice as deep is 2 atan(2 tan 20) wide.
  r = run("render " + scene.string() + " --views 3 --size 48x36 --cone 40 --fov 90 --depthiness 2 --out " +
          d.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto m2 = nlohmann::json::parse(std::ifstream(d / "manifest.json"));
  const double pi = 3.14159265358979323846;
  EXPECT_NEAR(m2["camera"]["fov_deg"].get<double>(), 90.0, 1e-9);
  EXPECT_NEAR(m2["camera"]["cone_deg"].get<double>(), 2.0 * std::atan(2.0 * std::tan(20.0 * pi / 180.0)) * 180.0 / pi,
              1e-9);
  for (const char* bad : {"--cone 180", "--fov 0", "--focal near", "--depthiness -1", "--background 2,0,0",
                          "--background red"}) {
    Result e = run(std::string("render --views 2 --size 16x12 ") + bad + " --out " + d.string());
    EXPECT_NE(e.status, 0) << bad;
    EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << bad << ": " << e.err;
  }
}

// A folder holds one set: a smaller render into a folder that held a
// larger one, with a quilt and depth maps, leaves only its own files.
TEST(Cli, RerenderingLeavesNoStaleFiles) {
  const fs::path d = outDir("stale");
  Result r = run("render --backend svr --views 6 --size 32x24 --depth --quilt auto --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.err;
  std::ofstream(d / "notes.txt") << "the user's own file";
  r = run("render --backend svr --views 3 --size 32x24 --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.err;
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(d)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"manifest.json", "notes.txt", "view_0000.png", "view_0001.png",
                                             "view_0002.png"}));
  const auto m = nlohmann::json::parse(std::ifstream(d / "manifest.json"));
  EXPECT_EQ(m["stale_files_removed"], 10);  // 3 views, 6 depth maps, a quilt
}

// Quilts (issue 19, deliverable 2): a display preset sets views and
// layout, the file carries Looking Glass's metadata in EXIF UserComment
// (read back through OpenImageIO), grids parse strictly, and a grid with
// empty tiles says so.
TEST(Cli, QuiltPresetsMetadataAndStrictGrids) {
  const fs::path d = outDir("quilt_preset");
  Result r = run("render --backend mvr --pst cpu --quilt portrait --size 42x56 --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto m = nlohmann::json::parse(std::ifstream(d / "manifest.json"));
  EXPECT_EQ(m["views"], 48);  // 8 x 6
  EXPECT_EQ(m["quilt"], "quilt_qs8x6a0.75.png");
  EXPECT_EQ(m["quilt_layout"]["preset"], "portrait");
  const std::string comment = mvr::readImageAttribute((d / "quilt_qs8x6a0.75.png").string(), "Exif:UserComment");
  ASSERT_FALSE(comment.empty());
  const auto lkg = nlohmann::json::parse(comment);
  EXPECT_EQ(lkg["LKGNumViews"], 48);
  EXPECT_EQ(lkg["LKGColumns"], 8);
  EXPECT_EQ(lkg["LKGRows"], 6);
  EXPECT_EQ(lkg["LKGAspect"], 0.75);
  // --quilt-only: the quilt and the manifest, no views (the earlier set's
  // views are gone too).
  r = run("render --backend svr --views 6 --size 16x12 --quilt-only --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.err;
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(d)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"manifest.json", "quilt_qs2x3a1.33.png"}));
  // 10 views in an 8x6 grid (X accepted as x): done, with a warning.
  r = run("render --backend svr --views 10 --size 16x12 --quilt 8X6 --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("leaves 38 of its tiles empty"), std::string::npos) << r.err;
  for (const char* bad : {"8x6.5", "8x6x3360", "0x6", "-8x6", "8x", "lookingglass"}) {
    Result e = run(std::string("render --views 2 --size 16x12 --quilt ") + bad + " --out " + d.string());
    EXPECT_NE(e.status, 0) << bad;
    EXPECT_NE(e.err.find("--quilt"), std::string::npos) << bad << ": " << e.err;
    EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << bad << ": " << e.err;
  }
}

// Anti-aliasing (issue 19, deliverable 4): the images keep the asked-for
// size, edges get partial alpha, the manifest says how; bad counts fail.
TEST(Cli, AntialiasingKeepsTheSizeAndSaysHow) {
  const fs::path d = outDir("aa");
  Result r = run("render --backend mvr --pst cpu --views 4 --size 32x24 --aa 2 --aa-views 2 --quilt auto --out " +
                 d.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const mvr::Image view = mvr::readImage((d / "view_0002.png").string());
  EXPECT_EQ(view.width, 32);
  EXPECT_EQ(view.height, 24);
  int partial = 0;
  for (int y = 0; y < view.height; ++y)
    for (int x = 0; x < view.width; ++x) partial += view.row(y)[x * 4 + 3] % 255 != 0;
  EXPECT_GT(partial, 10);
  const auto m = nlohmann::json::parse(std::ifstream(d / "manifest.json"));
  EXPECT_EQ(m["antialiasing"]["samples_per_pixel"], 4);
  EXPECT_EQ(m["antialiasing"]["samples_per_view"], 2);
  EXPECT_EQ(m["views"], 4);
  for (const char* bad : {"--aa 0", "--aa 9", "--aa-views 17", "--aa-views 2 --views 1"}) {
    Result e = run(std::string("render --size 16x12 ") + bad + " --out " + d.string());
    EXPECT_NE(e.status, 0) << bad;
    EXPECT_NE(e.err.find("--aa"), std::string::npos) << bad << ": " << e.err;
    EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << bad << ": " << e.err;
  }
  EXPECT_TRUE(fs::exists(d / "view_0003.png")) << "a failed render leaves the set alone";
}

// Issue 19's done-when: a bare mesh to a Looking Glass quilt with a 40
// degree cone and the focal plane through the object's centre, in one
// command; the quilt carries its metadata and the viewer opens it.
TEST(Cli, FromABareMeshToALookingGlassQuiltInOneCommand) {
  const fs::path d = outDir("lkg_one_command");
  Result r = run("render " + test::assetsDir() + "/teacup_4k.ply --quilt portrait --size 42x56 --cone 40 "
                 "--focal center --quilt-only --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto m = nlohmann::json::parse(std::ifstream(d / "manifest.json"));
  EXPECT_NEAR(m["camera"]["cone_deg"].get<double>(), 40.0, 1e-9);
  EXPECT_EQ(m["views"], 48);
  const fs::path quilt = d / m["quilt"].get<std::string>();
  const auto lkg = nlohmann::json::parse(mvr::readImageAttribute(quilt.string(), "Exif:UserComment"));
  EXPECT_EQ(lkg["LKGNumViews"], 48);
  EXPECT_EQ(lkg["LKGColumns"], 8);
  EXPECT_EQ(lkg["LKGRows"], 6);
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) GTEST_SKIP() << "no xvfb-run";
  const auto viewed = test::shell("xvfb-run -a " + test::mvrBinary() + " view " + quilt.string() +
                                  " --screenshot " + (d / "shot.png").string());
  ASSERT_EQ(viewed.status, 0) << viewed.err;
  const mvr::Image shot = mvr::readImage((d / "shot.png").string());
  EXPECT_EQ(shot.width, 42);
  EXPECT_EQ(shot.height, 56 + 48);
}

// A scene file of a glTF and an OBJ with its MTL (tests/support/
// asset_scene.h) through the outputs a user asks for: a Portrait quilt
// with depth maps by MVR, and the EPI stream.
TEST(Cli, RealAssetsToAQuiltDepthMapsAndAStream) {
  const fs::path d = outDir("real_assets");
  const std::string scene = test::writeAssetScene(d / "scene");
  Result r = run("render " + scene + " --quilt portrait --size 42x56 --depth --out " + (d / "quilt").string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto m = nlohmann::json::parse(std::ifstream(d / "quilt" / "manifest.json"));
  EXPECT_EQ(m["views"], 48);
  EXPECT_EQ(m["notes"]["passes"], "diffuse+texture+view-dependent");
  const mvr::Image quilt = mvr::readImage((d / "quilt" / m["quilt"].get<std::string>()).string());
  EXPECT_EQ(quilt.width, 8 * 42);
  EXPECT_EQ(quilt.height, 6 * 56);
  EXPECT_TRUE(fs::exists(d / "quilt" / "depth_0047.exr"));
  const fs::path stream = d / "epis.bin";
  r = run("stream " + scene + " --views 8 --size 48x32 --to " + stream.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_GT(fs::file_size(stream), size_t(48) * 8 * 32 * 4);
}

TEST(Cli, BenchPlotsAgainFromItsJson) {
  const fs::path d = outDir("replot");
  fs::create_directories(d);
  const fs::path json = d / "bench.json";
  ASSERT_EQ(run("bench --views 1,4 --size 40x30 --backends svr,mvr:quad,interp:center:c1 --json " +
                json.string()).status, 0);
  const Result r = run("bench --replot " + json.string() + " --plots " + (d / "plots").string());
  EXPECT_EQ(r.status, 0) << r.err;
  for (const char* plot : {"time_per_view_40x30.gp", "backends_40x30.gp", "psnr_vs_time_40x30.gp"})
    EXPECT_TRUE(fs::exists(d / "plots" / plot)) << plot;
  std::ifstream backends(d / "plots" / "backends_40x30.gp");
  const std::string script((std::istreambuf_iterator<char>(backends)), {});
  EXPECT_NE(script.find("interp:center:c1"), std::string::npos);
  // Not a benchmark's JSON, no such file, no --plots: one line each.
  std::ofstream(d / "other.json") << R"({"views": 3})";
  for (const std::string& args : {"bench --replot " + (d / "other.json").string() + " --plots " + d.string(),
                                  "bench --replot /nonexistent/bench.json --plots " + d.string(),
                                  "bench --replot " + json.string()}) {
    const Result bad = run(args);
    EXPECT_NE(bad.status, 0) << args;
    EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << args << ": " << bad.err;
  }
}

TEST(Cli, HelpForEverySubcommand) {
  for (std::string c : {"info", "render", "stream", "synthesize", "view", "compare", "bench"})
    EXPECT_EQ(run(c + " --help").status, 0) << c;
}

// Issue 19's small things: a repeated option and an option that swallows
// the next one are one-line errors naming it; the summary names views and
// the back end once, after one prefix.
TEST(Cli, RepeatedOptionsAndTheSummaryLine) {
  const fs::path d = outDir("polish");
  for (const char* bad : {"--views 3 --views 4", "--views --out"}) {
    Result e = run(std::string("render --size 16x12 ") + bad + " " + d.string());
    EXPECT_NE(e.status, 0) << bad;
    EXPECT_EQ(e.err.rfind("mvr: --views", 0), 0u) << bad << ": " << e.err;
    EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << bad << ": " << e.err;
  }
  Result r = run("render --backend svr --views 2 --size 16x12 --out " + d.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err.rfind("mvr: rendered 2 views of 16x12 with svr to ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find("mvr: mvr"), std::string::npos) << r.err;
}

// Errors read as ours: one "mvr: " prefix, and arguments nobody takes
// named in the order given (CLI11 lists them as it parsed them, backwards).
TEST(Cli, UnknownCommandsAndUnexpectedArgumentsInTheOrderGiven) {
  Result c = run("lenticular");
  EXPECT_EQ(c.status, 1);
  EXPECT_EQ(c.err, "mvr: unknown command 'lenticular' (expected info, render, stream, synthesize, view, native, live, "
                   "compare or bench)\n");
  const fs::path d = outDir("extras");
  Result e = run("render " + test::assetsDir() + "/cube.obj extra --bogus --out " + d.string());
  EXPECT_EQ(e.status, 1);
  EXPECT_EQ(e.err, "mvr: unexpected arguments extra --bogus (see mvr render --help)\n");
  EXPECT_FALSE(fs::exists(d));
  Result one = run("info --frames");
  EXPECT_EQ(one.err, "mvr: unexpected argument --frames (see mvr info --help)\n");
}

// docs/CLI.md is what the programs' --help prints (scripts/cli-doc): the
// options are declared once, and the reference cannot drift from them.
TEST(Cli, ReferenceDocsMatchTheHelp) {
  const fs::path source = MVR_TEST_SOURCE;
  const fs::path generated = fs::temp_directory_path() / ("mvr_cli_doc_" + std::to_string(getpid()) + ".md");
  const std::string cmd = "MVR=" + test::mvrBinary() + " MVR_CONSUME=" + test::consumeBinary() + " bash " +
                          (source / "scripts/cli-doc").string() + " --stdout >" + generated.string();
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  std::stringstream expected, actual;
  expected << std::ifstream(source / "docs/CLI.md").rdbuf();
  actual << std::ifstream(generated).rdbuf();
  fs::remove(generated);
  EXPECT_GT(actual.str().size(), 1000u);
  EXPECT_TRUE(expected.str() == actual.str()) << "docs/CLI.md disagrees with the programs' --help: run scripts/cli-doc";
}

TEST(Cli, VersionPrintsTheProjectVersion) {
  const std::string cmd = test::mvrBinary() + " --version | grep -qx 'mvr [0-9]*\\.[0-9]*\\.[0-9]*'";
  EXPECT_EQ(std::system(cmd.c_str()), 0);
}

}  // namespace
