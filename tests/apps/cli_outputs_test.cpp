// mvr's outputs as a user asks for them: depth maps, warped and
// synthesized tracks, display cameras, quilts, anti-aliasing, and a bare
// or real mesh to a quilt in one command.
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

// --depth: a float exr beside every view of a grid, 0 exactly where the
// view is empty, the same surfaces as svr's depth (mvr's CPU spans are
// exact), and the manifest says what the files hold. Where a pixel centre
// lies within the GL's sub-pixel snapping of an edge between two surfaces,
// the fill rule may give it either (render_helpers.h: well under 0.5% of
// pixels; 0.23% on an NVIDIA H100, none on llvmpipe).
TEST(Cli, DepthMapsBesideEveryView) {
  const fs::path mvr = test::freshDir("cli_depth_mvr"), svr = test::freshDir("cli_depth_svr");
  const std::string common = " --views 3 --rows 2 --size 40x30 --depth --out ";
  test::CliResult r = test::runMvr("render --backend mvr --pst cpu" + common + mvr.string());
  ASSERT_TRUE(test::succeeded(r));
  r = test::runMvr("render --backend svr" + common + svr.string());
  ASSERT_TRUE(test::succeeded(r));
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
// at the worst view, 64.5 at the references), the CPU's silhouettes on the
// pixel grid as GL's (--outline-samples 1; with the sources' finer outline
// they end inside pixels, which the GL grid cannot: WarpOnTheCpu).
TEST(Cli, WarpsByGlAndOnTheCpu) {
  const fs::path gl = test::freshDir("cli_warp_gl"), cpu = test::freshDir("cli_warp_cpu");
  for (const auto& [path, dir] : {std::pair{"gl", gl}, std::pair{"cpu", cpu}}) {
    const test::CliResult r = test::runMvr(std::string("render --backend warp --outline-samples 1 --warp-path ") +
                                           path + " --views 5 --size 96x72 --out " + dir.string());
    ASSERT_TRUE(test::succeeded(r));
    test::expectSet(dir, 5, "warp");
  }
  for (int view = 0; view < 5; ++view) {
    char name[32];
    std::snprintf(name, sizeof name, "view_%04d.png", view);
    const mvr::ImageDifference diff =
        mvr::compareImages(mvr::readImage((gl / name).string()), mvr::readImage((cpu / name).string()));
    EXPECT_GE(diff.psnr, 40.0) << name;
  }
  // A finer outline the GL grid cannot draw is an error, not ignored.
  const test::CliResult e =
      test::runMvr("render --backend warp --outline-samples 4 --warp-path gl --views 2 --size 16x12 --out " + gl.string());
  EXPECT_TRUE(test::failed(e));
  EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << e.err;
  EXPECT_NE(e.err.find("--outline-samples"), std::string::npos) << e.err;
}

// RGB-D out, then in: three svr views with depth, synthesized into nine
// views and a quilt by the warp back end; the views at the references are
// the references, those between close to svr's.
TEST(Cli, SynthesizesATrackFromRgbdReferences) {
  const fs::path refs = test::freshDir("cli_syn_refs"), out = test::freshDir("cli_syn_out"), svr = test::freshDir("cli_syn_svr");
  test::CliResult r = test::runMvr("render --backend svr --views 3 --size 128x96 --depth --out " + refs.string());
  ASSERT_TRUE(test::succeeded(r));
  r = test::runMvr("synthesize --from " + refs.string() + " --views 9 --quilt auto --out " + out.string());
  ASSERT_TRUE(test::succeeded(r));
  r = test::runMvr("render --backend svr --views 9 --size 128x96 --out " + svr.string());
  ASSERT_TRUE(test::succeeded(r));
  test::expectSet(out, 9, "warp");
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
  const fs::path d = test::freshDir("cli_display_camera"), mesh = test::freshDir("cli_display_mesh") / "quad.obj";
  fs::create_directories(mesh.parent_path());
  std::ofstream(mesh) << "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nf 1 2 3\nf 1 3 4\n";
  // A scene file, as a bare mesh is centred on load.
  const fs::path scene = mesh.parent_path() / "quad.json";
  std::ofstream(scene) << R"({"meshes": [{"file": "quad.obj", "transform": {"translate": [0, 0, 0.5]}}]})";
  test::CliResult r = test::runMvr("render " + scene.string() + " --backend mvr --pst cpu --views 5 --size 48x36 --cone 40 "
                 "--focal center --background 0.25,0.25,0.25 --opaque --quilt auto --out " + d.string());
  ASSERT_TRUE(test::succeeded(r));
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
  r = test::runMvr("render " + scene.string() + " --views 3 --size 48x36 --cone 40 --fov 90 --depthiness 2 --out " +
          d.string());
  ASSERT_TRUE(test::succeeded(r));
  const auto m2 = nlohmann::json::parse(std::ifstream(d / "manifest.json"));
  const double pi = 3.14159265358979323846;
  EXPECT_NEAR(m2["camera"]["fov_deg"].get<double>(), 90.0, 1e-9);
  EXPECT_NEAR(m2["camera"]["cone_deg"].get<double>(), 2.0 * std::atan(2.0 * std::tan(20.0 * pi / 180.0)) * 180.0 / pi,
              1e-9);
  for (const char* bad : {"--cone 180", "--fov 0", "--focal near", "--depthiness -1", "--background 2,0,0",
                          "--background red"}) {
    test::CliResult e = test::runMvr(std::string("render --views 2 --size 16x12 ") + bad + " --out " + d.string());
    EXPECT_TRUE(test::failed(e)) << bad;
    EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << bad << ": " << e.err;
  }
}

// A bare mesh is centred on load and --focal moves it behind the plane:
// the manifest's from_file takes the file's points to the coordinates V
// is in, so the file's own centre lands on the middle view's axis at the
// camera distance (an outside check, scripts/threejs-check, needs it).
TEST(Cli, ManifestTakesTheFilesCoordinates) {
  const fs::path d = test::freshDir("cli_from_file"), mesh = test::freshDir("cli_from_file_mesh") / "quad.obj";
  fs::create_directories(mesh.parent_path());
  std::ofstream(mesh) << "v 2 1 0\nv 4 1 0\nv 4 3 1\nv 2 3 1\nf 1 2 3\nf 1 3 4\n";
  test::CliResult r = test::runMvr("render " + mesh.string() + " --views 3 --size 32x24 --focal center --out " + d.string());
  ASSERT_TRUE(test::succeeded(r));
  const auto m = nlohmann::json::parse(std::ifstream(d / "manifest.json"));
  const nlohmann::json& f = m["cameras"]["from_file"];
  const nlohmann::json& v = m["cameras"]["views"][1]["V"];
  const double centre[4] = {3.0, 2.0, 0.5, 1.0};
  double scene[4] = {0, 0, 0, 0}, camera[4] = {0, 0, 0, 0};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) scene[r] += f[r][c].get<double>() * centre[c];
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) camera[r] += v[r][c].get<double>() * scene[c];
  EXPECT_NEAR(scene[0], 0.0, 1e-6);  // centred
  EXPECT_NEAR(scene[1], 0.0, 1e-6);
  EXPECT_NEAR(camera[0], 0.0, 1e-6);
  EXPECT_NEAR(camera[1], 0.0, 1e-6);
  EXPECT_NEAR(camera[2], m["camera"]["distance"].get<double>(), 1e-6);
  // A scene file's coordinates are the scene's: no from_file.
  const fs::path scene_file = mesh.parent_path() / "quad.json";
  std::ofstream(scene_file) << R"({"meshes": [{"file": "quad.obj"}]})";
  r = test::runMvr("render " + scene_file.string() + " --views 3 --size 32x24 --out " + d.string());
  ASSERT_TRUE(test::succeeded(r));
  EXPECT_FALSE(nlohmann::json::parse(std::ifstream(d / "manifest.json"))["cameras"].contains("from_file"));
}

// A folder holds one set: a smaller render into a folder that held a
// larger one, with a quilt and depth maps, leaves only its own files.
TEST(Cli, RerenderingLeavesNoStaleFiles) {
  const fs::path d = test::freshDir("cli_stale");
  test::CliResult r = test::runMvr("render --backend svr --views 6 --size 32x24 --depth --quilt auto --out " + d.string());
  ASSERT_TRUE(test::succeeded(r));
  std::ofstream(d / "notes.txt") << "the user's own file";
  r = test::runMvr("render --backend svr --views 3 --size 32x24 --out " + d.string());
  ASSERT_TRUE(test::succeeded(r));
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
  const fs::path d = test::freshDir("cli_quilt_preset");
  test::CliResult r = test::runMvr("render --backend mvr --pst cpu --quilt portrait --size 42x56 --out " + d.string());
  ASSERT_TRUE(test::succeeded(r));
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
  r = test::runMvr("render --backend svr --views 6 --size 16x12 --quilt-only --out " + d.string());
  ASSERT_TRUE(test::succeeded(r));
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(d)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"manifest.json", "quilt_qs2x3a1.33.png"}));
  // 10 views in an 8x6 grid (X accepted as x): done, with a warning.
  r = test::runMvr("render --backend svr --views 10 --size 16x12 --quilt 8X6 --out " + d.string());
  ASSERT_TRUE(test::succeeded(r));
  EXPECT_NE(r.err.find("leaves 38 of its tiles empty"), std::string::npos) << r.err;
  for (const char* bad : {"8x6.5", "8x6x3360", "0x6", "-8x6", "8x", "lookingglass"}) {
    test::CliResult e = test::runMvr(std::string("render --views 2 --size 16x12 --quilt ") + bad + " --out " + d.string());
    EXPECT_TRUE(test::failed(e)) << bad;
    EXPECT_NE(e.err.find("--quilt"), std::string::npos) << bad << ": " << e.err;
    EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << bad << ": " << e.err;
  }
}

// Anti-aliasing (issue 19, deliverable 4): the images keep the asked-for
// size, edges get partial alpha, the manifest says how; bad counts fail.
TEST(Cli, AntialiasingKeepsTheSizeAndSaysHow) {
  const fs::path d = test::freshDir("cli_aa");
  test::CliResult r = test::runMvr("render --backend mvr --pst cpu --views 4 --size 32x24 --aa 2 --aa-views 2 --quilt auto --out " +
                 d.string());
  ASSERT_TRUE(test::succeeded(r));
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
    test::CliResult e = test::runMvr(std::string("render --size 16x12 ") + bad + " --out " + d.string());
    EXPECT_TRUE(test::failed(e)) << bad;
    EXPECT_NE(e.err.find("--aa"), std::string::npos) << bad << ": " << e.err;
    EXPECT_EQ(std::count(e.err.begin(), e.err.end(), '\n'), 1) << bad << ": " << e.err;
  }
  EXPECT_TRUE(fs::exists(d / "view_0003.png")) << "a failed render leaves the set alone";
}

// Issue 19's done-when: a bare mesh to a Looking Glass quilt with a 40
// degree cone and the focal plane through the object's centre, in one
// command; the quilt carries its metadata and the viewer opens it.
TEST(Cli, FromABareMeshToALookingGlassQuiltInOneCommand) {
  const fs::path d = test::freshDir("cli_lkg_one_command");
  test::CliResult r = test::runMvr("render " + test::assetsDir() + "/teacup_4k.ply --quilt portrait --size 42x56 --cone 40 "
                 "--focal center --quilt-only --out " + d.string());
  ASSERT_TRUE(test::succeeded(r));
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
  ASSERT_TRUE(test::succeeded(viewed));
  const mvr::Image shot = mvr::readImage((d / "shot.png").string());
  EXPECT_EQ(shot.width, 42);
  EXPECT_EQ(shot.height, 56 + 48);
}

// A scene file of a glTF and an OBJ with its MTL (tests/support/
// asset_scene.h) through the outputs a user asks for: a Portrait quilt
// with depth maps by MVR, and the EPI stream.
TEST(Cli, RealAssetsToAQuiltDepthMapsAndAStream) {
  const fs::path d = test::freshDir("cli_real_assets");
  const std::string scene = test::writeAssetScene(d / "scene");
  test::CliResult r = test::runMvr("render " + scene + " --quilt portrait --size 42x56 --depth --out " + (d / "quilt").string());
  ASSERT_TRUE(test::succeeded(r));
  const auto m = nlohmann::json::parse(std::ifstream(d / "quilt" / "manifest.json"));
  EXPECT_EQ(m["views"], 48);
  EXPECT_EQ(m["notes"]["passes"], "diffuse+texture+view-dependent");
  const mvr::Image quilt = mvr::readImage((d / "quilt" / m["quilt"].get<std::string>()).string());
  EXPECT_EQ(quilt.width, 8 * 42);
  EXPECT_EQ(quilt.height, 6 * 56);
  EXPECT_TRUE(fs::exists(d / "quilt" / "depth_0047.exr"));
  const fs::path stream = d / "epis.bin";
  r = test::runMvr("stream " + scene + " --views 8 --size 48x32 --to " + stream.string());
  ASSERT_TRUE(test::succeeded(r));
  EXPECT_GT(fs::file_size(stream), size_t(48) * 8 * 32 * 4);
}

}  // namespace
