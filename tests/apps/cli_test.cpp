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

#include "mvr/images/compare.h"
#include "mvr/images/image_file.h"
#include "mvr/images/manifest.h"
#include "tests/support/asset_scene.h"
#include "tests/support/cli.h"
#include "tests/support/gl_fixture.h"
#include "tests/support/image_set.h"

namespace {

namespace test = mvr::test;

namespace fs = std::filesystem;

TEST(Cli, RendersDefaultSceneUnderEgl) {
  fs::path d = test::freshDir("cli_egl");
  test::CliResult r = test::runMvr("render --gl egl --views 4 --size 48x36 --out " + d.string());
  ASSERT_TRUE(test::succeeded(r));
  test::expectSet(d, 4, "mvr");
}

TEST(Cli, RendersDefaultSceneUnderOsMesa) {
  fs::path d = test::freshDir("cli_osmesa");
  test::CliResult r = test::runMvr("render --gl osmesa --views 3 --size 40x30 --out " + d.string());
  // A GPU host runs the suite with GL forced to EGL (scripts/gpu-tests) and
  // has no OSMesa; everywhere else its absence is a failure.
  const char* forced = std::getenv("MVR_TEST_GL");
  if (r.status != 0 && forced && std::string(forced) == "egl" && r.err.find("libOSMesa") != std::string::npos)
    GTEST_SKIP() << r.err;
  ASSERT_TRUE(test::succeeded(r));
  test::expectSet(d, 3, "mvr");
}

TEST(Cli, EveryBaselineWritesItsSet) {
  for (std::string b : {"svr-layered", "deferred"}) {
    fs::path d = test::freshDir("cli_" + b);
    test::CliResult r = test::runMvr("render --backend " + b + " --views 3 --size 40x30 --out " + d.string());
    ASSERT_TRUE(test::succeeded(r));
    test::expectSet(d, 3, b);
  }
}

TEST(Cli, CompareReportsIdenticalAndRejectsMismatch) {
  fs::path a = test::freshDir("cli_cmp_a"), b = test::freshDir("cli_cmp_b"), c = test::freshDir("cli_cmp_c");
  ASSERT_TRUE(test::succeeded(test::runMvr("render --views 2 --size 40x30 --out " + a.string())));
  ASSERT_TRUE(test::succeeded(test::runMvr("render --views 2 --size 40x30 --out " + b.string())));
  ASSERT_TRUE(test::succeeded(test::runMvr("render --views 2 --size 42x30 --out " + c.string())));
  EXPECT_TRUE(test::succeeded(test::runMvr("compare " + a.string() + " " + b.string())));
  test::CliResult mismatch = test::runMvr("compare " + a.string() + " " + c.string());
  EXPECT_TRUE(test::failed(mismatch));
  EXPECT_NE(mismatch.err.find("size mismatch"), std::string::npos) << mismatch.err;
}

TEST(Cli, BadInputGivesOneLineErrorAndNoSet) {
  fs::path d = test::freshDir("cli_bad");
  const fs::path noTexture = test::freshDir("cli_bad_scene") / "missing_texture.json";
  fs::create_directories(noTexture.parent_path());
  std::ofstream(noTexture) << R"({"meshes": [{"file": ")" << test::assetsDir()
                           << R"(/plane.obj", "material": {"texture": "nothere.png"}}]})";
  // A square image is neither a cube strip (6:1) nor a sphere map pair (2:1).
  const fs::path squareMap = noTexture.parent_path() / "square_map.json";
  std::ofstream(squareMap) << R"({"meshes": [{"file": ")" << test::assetsDir()
                           << R"(/plane.obj", "material": {"reflection_map": ")" << test::assetsDir()
                           << R"(/checker.png"}}]})";
  // A scene file's environment with an intensity that is not a number.
  const fs::path badEnvironment = noTexture.parent_path() / "bad_environment.json";
  std::ofstream(badEnvironment) << R"({"meshes": [{"file": ")" << test::assetsDir()
                                << R"(/plane.obj"}], "environment": {"file": "sky.exr", "intensity": "bright"}})";
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
                           "render --exposure bright --out " + d.string(),
                           "render --exposure 1e9 --out " + d.string(),
                           "render --tonemap filmic --out " + d.string(),
                           "render --environment /nonexistent/sky.exr --out " + d.string(),
                           "render --environment " + test::assetsDir() + "/checker.png --out " + d.string(),
                           "render --environment-intensity 2 --out " + d.string(),
                           "render --environment-intensity -1 --out " + d.string(),
                           "render " + badEnvironment.string() + " --out " + d.string(),
                           "render --tonemap aces --format exr --out " + d.string(),
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
    test::CliResult r = test::runMvr(args);
    EXPECT_TRUE(test::failed(r)) << args;
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
        {"12X", "mvr: --memory: '12X' is not a size"},
        {"--exposure bright", "--exposure: must be auto or a number of stops"},
        {"--format exr", "mvr: --tonemap: exr keeps linear radiance"},
        {"/nonexistent/sky.exr", "/nonexistent/sky.exr"},
        {"checker.png --out", "checker.png: an environment must be an equirectangular (2:1) map"},
        {"--environment-intensity 2", "mvr: --environment-intensity: the scene has no environment"},
        {"bad_environment.json", "bad_environment.json: environment.intensity"}};
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
    const fs::path d = test::freshDir("cli_encoding");
    const test::CliResult r = test::runMvr("render --views 2 --size 32x24 " + c.flags + " --out " + d.string());
    ASSERT_TRUE(test::succeeded(r)) << c.flags;
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
    const fs::path d = test::freshDir("cli_encoding_bad");
    const test::CliResult r = test::runMvr("render --views 2 --size 32x24 " + flags + " --out " + d.string());
    EXPECT_TRUE(test::failed(r)) << flags;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << flags << ": " << r.err;
    EXPECT_NE(r.err.find(flags.find("codec") != std::string::npos ? "--codec" : "--bits"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(d / "manifest.json")) << flags;
  }
}

TEST(Cli, DroppedFacesWarnAndStrictRefuses) {
  const fs::path d = test::freshDir("cli_dropped");
  const fs::path ply = test::freshDir("cli_dropped_scene") / "bad_index.ply";
  fs::create_directories(ply.parent_path());
  std::ofstream(ply) << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
                        "property float z\nelement face 3\nproperty list uchar int vertex_indices\nend_header\n"
                        "0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n3 0 1 7\n";
  const std::string args = "render " + ply.string() + " --views 2 --size 32x24 --out " + d.string();
  test::CliResult r = test::runMvr(args);
  EXPECT_TRUE(test::succeeded(r));
  EXPECT_NE(r.err.find("mvr: warning: " + ply.string() + ": 1 faces dropped"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(d / "manifest.json"));
  fs::remove_all(d);
  r = test::runMvr(args + " --strict");
  EXPECT_TRUE(test::failed(r));
  EXPECT_EQ(r.err, "mvr: " + ply.string() +
                       ": 1 faces dropped (a repeated corner or a vertex that does not exist) (--strict)\n");
  EXPECT_FALSE(fs::exists(d / "manifest.json"));
}

// A file-size limit (as a full disk would) fails the write: one line naming
// the file and the system's reason, non-zero status, and no set left that
// looks complete (before, truncated PNGs and a manifest were committed).
TEST(Cli, FailedWritesLeaveNoSet) {
  const fs::path d = test::freshDir("cli_efbig");
  const fs::path stream = test::freshDir("cli_efbig_stream") / "s.bin";
  fs::create_directories(stream.parent_path());
  for (const std::string& args : {"render --views 4 --size 320x240 --out " + d.string(),
                                  "render --views 4 --size 320x240 --format exr --out " + d.string(),
                                  "stream --views 4 --size 320x240 --to " + stream.string()}) {
    const test::CliResult r = test::shell("ulimit -f 16; " + test::mvrBinary() + " " + args + " >/dev/null");
    EXPECT_TRUE(test::failed(r)) << args;
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
  const fs::path d = test::freshDir("cli_no_codec");
  const std::string noModule = "MVR_IMAGE_CODEC=/nonexistent/libmvr_oiio.so " + test::mvrBinary();
  test::CliResult r = test::shell(noModule + " render --views 2 --size 16x12 --out " + d.string() + " >/dev/null");
  ASSERT_TRUE(test::succeeded(r));
  EXPECT_EQ(mvr::readImage((d / "view_0001.png").string()).width, 16);
  r = test::shell(noModule + " render --views 2 --size 16x12 --format exr --out " + d.string() + " >/dev/null");
  EXPECT_TRUE(test::failed(r));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("mvr: /nonexistent/libmvr_oiio.so: cannot load the image codec module"), std::string::npos)
      << r.err;
  EXPECT_FALSE(fs::exists(d / "manifest.json"));
}

TEST(Cli, RendersUnderGlfwWithAVirtualDisplay) {
  if (std::system("command -v xvfb-run >/dev/null 2>&1") != 0) GTEST_SKIP() << "no xvfb-run";
  fs::path d = test::freshDir("cli_glfw");
  const std::string cmd = "xvfb-run -a " + test::mvrBinary() +
                          " render --gl glfw --views 2 --size 32x24 --out " + d.string() + " >/dev/null";
  ASSERT_TRUE(test::succeeded(test::shell(cmd)));
  test::expectSet(d, 2, "mvr");
  auto m = nlohmann::json::parse(std::ifstream(d / "manifest.json"));
  EXPECT_EQ(m["gl"]["platform"], "glfw");
}

TEST(Cli, MvrWritesEpisAndStats) {
  fs::path d = test::freshDir("cli_epis");
  test::CliResult r = test::runMvr("render --backend mvr --pst cpu --order epi --views 5 --size 40x30 --out " + d.string());
  ASSERT_TRUE(test::succeeded(r));
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
  r = test::runMvr("render --backend mvr --pst cpu --format exr --views 2 --size 16x12 --out " + d.string());
  ASSERT_TRUE(test::succeeded(r));
  m = nlohmann::json::parse(std::ifstream(d / "manifest.json"));
  EXPECT_GT(m["startup_s"]["image_module_load"].get<double>(), 0.0);
}

// With no --pst, mvr and interp take the CPU spans where GL renders on the
// CPU (exact, and several times the GL modes' speed there), and on a GPU
// the GPU spans where they shade the scene, else their GL defaults; a
// named mode, texture mode or PST builder is kept.
TEST(Cli, TheDefaultAccuracyModeFollowsWhereGlRenders) {
  const fs::path d = test::freshDir("cli_default_pst");
  auto pstOf = [&](const std::string& args) {
    const test::CliResult r = test::runMvr("render " + args + " --views 3 --size 40x30 --out " + d.string());
    EXPECT_TRUE(test::succeeded(r));
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

TEST(Cli, BenchPlotsAgainFromItsJson) {
  const fs::path d = test::freshDir("cli_replot");
  fs::create_directories(d);
  const fs::path json = d / "bench.json";
  ASSERT_TRUE(test::succeeded(
      test::runMvr("bench --views 1,4 --size 40x30 --backends svr,mvr:quad,interp:center:c1 --json " + json.string())));
  const test::CliResult r = test::runMvr("bench --replot " + json.string() + " --plots " + (d / "plots").string());
  EXPECT_TRUE(test::succeeded(r));
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
    const test::CliResult bad = test::runMvr(args);
    EXPECT_TRUE(test::failed(bad)) << args;
    EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << args << ": " << bad.err;
  }
}

TEST(Cli, HelpForEverySubcommand) {
  for (std::string c : {"info", "render", "stream", "synthesize", "view", "compare", "bench"})
    EXPECT_TRUE(test::succeeded(test::runMvr(c + " --help"))) << c;
}

// Issue 19's small things: a repeated option and an option that swallows
// the next one are one-line errors naming it; the summary names views and
// the back end once, after one prefix.
TEST(Cli, RepeatedOptionsAndTheSummaryLine) {
  const fs::path d = test::freshDir("cli_polish");
  for (const char* bad : {"--views 3 --views 4", "--views --out"}) {
    test::CliResult e = test::runMvr(std::string("render --size 16x12 ") + bad + " " + d.string());
    EXPECT_TRUE(test::failed(e)) << bad;
    EXPECT_EQ(e.err.rfind("mvr: --views", 0), 0u) << bad << ": " << e.err;
    EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << bad << ": " << e.err;
  }
  test::CliResult r = test::runMvr("render --backend svr --views 2 --size 16x12 --out " + d.string());
  ASSERT_TRUE(test::succeeded(r));
  EXPECT_EQ(r.err.rfind("mvr: rendered 2 views of 16x12 with svr to ", 0), 0u) << r.err;
  EXPECT_EQ(r.err.find("mvr: mvr"), std::string::npos) << r.err;
}

// Errors read as ours: one "mvr: " prefix, and arguments nobody takes
// named in the order given (CLI11 lists them as it parsed them, backwards).
TEST(Cli, UnknownCommandsAndUnexpectedArgumentsInTheOrderGiven) {
  test::CliResult c = test::runMvr("lenticular");
  EXPECT_TRUE(test::exitedWith(c, 1));
  EXPECT_EQ(c.err, "mvr: unknown command 'lenticular' (expected info, render, stream, synthesize, view, native, live, "
                   "compare or bench)\n");
  const fs::path d = test::freshDir("cli_extras");
  test::CliResult e = test::runMvr("render " + test::assetsDir() + "/cube.obj extra --bogus --out " + d.string());
  EXPECT_TRUE(test::exitedWith(e, 1));
  EXPECT_EQ(e.err, "mvr: unexpected arguments extra --bogus (see mvr render --help)\n");
  EXPECT_FALSE(fs::exists(d));
  test::CliResult one = test::runMvr("info --frames");
  EXPECT_EQ(one.err, "mvr: unexpected argument --frames (see mvr info --help)\n");
}

// docs/CLI.md is what the programs' --help prints (scripts/cli-doc): the
// options are declared once, and the reference cannot drift from them.
TEST(Cli, ReferenceDocsMatchTheHelp) {
  const fs::path source = MVR_TEST_SOURCE;
  const fs::path generated = fs::temp_directory_path() / ("mvr_cli_doc_" + std::to_string(getpid()) + ".md");
  const std::string cmd = "MVR=" + test::mvrBinary() + " MVR_CONSUME=" + test::consumeBinary() + " bash " +
                          (source / "scripts/cli-doc").string() + " --stdout >" + generated.string();
  ASSERT_TRUE(test::succeeded(test::shell(cmd)));
  std::stringstream expected, actual;
  expected << std::ifstream(source / "docs/CLI.md").rdbuf();
  actual << std::ifstream(generated).rdbuf();
  fs::remove(generated);
  EXPECT_GT(actual.str().size(), 1000u);
  EXPECT_TRUE(expected.str() == actual.str()) << "docs/CLI.md disagrees with the programs' --help: run scripts/cli-doc";
}

TEST(Cli, VersionPrintsTheProjectVersion) {
  const std::string cmd = test::mvrBinary() + " --version | grep -qx 'mvr [0-9]*\\.[0-9]*\\.[0-9]*'";
  EXPECT_TRUE(test::succeeded(test::shell(cmd)));
}

}  // namespace
