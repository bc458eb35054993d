// Output colour encoding (issue 15): 8- and 16-bit files hold sRGB-encoded
// values unless --linear, the files and the manifest say which, and every
// back end encodes from full precision. A plane lit by ambient light only
// has one colour, known by hand: diffuse (0.05, 0.2, 0.6) is linear bytes
// (12.75, 51, 153) and sRGB bytes (63.1, 123.5, 203.4).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "mvr/images/image_file.h"
#include "mvr/images/manifest.h"
#include "tests/support/cli.h"
#include "tests/support/gl_fixture.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;

const double kLinear[3] = {0.05, 0.2, 0.6};

double srgbByHand(double v) {
  return 255.0 * (v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055);
}

// The plane fills the middle of every view; `specular` adds a second
// shading pass (a highlight of zero, as there is no light), so the MVR
// back ends accumulate in float and encode through a blit.
fs::path planeScene(bool specular) {
  const fs::path file = test::freshDir(specular ? "color_scene2" : "color_scene1") / "plane.json";
  fs::create_directories(file.parent_path());
  std::ofstream(file) << R"({"meshes": [{"file": ")" << test::assetsDir() << R"(/plane.obj",
      "material": {"diffuse": [0.05, 0.2, 0.6])"
                      << (specular ? R"(, "specular": [0.001, 0.001, 0.001], "shininess": 4)" : "")
                      << R"(}}],
    "lights": [], "ambient": [1, 1, 1],
    "camera": {"distance": 4, "image_plane": 2.0, "track": [-0.5, 0.5], "near": 2, "far": 6}})";
  return file;
}

// Every view's centre pixel against the hand values, within GL's one step.
void expectCentres(const fs::path& set, bool srgb, const std::string& what) {
  const Manifest m = Manifest::read(set.string());
  EXPECT_EQ(m.colorEncoding(), srgb ? "srgb" : "linear") << what;
  for (int v = 0; v < m.views; ++v) {
    const std::string file = (set / m.viewName(0, v)).string();
    EXPECT_EQ(readImageEncoding(file).srgb, srgb) << what << ": the file's own tag";
    const Image img = readImage(file);
    const glm::vec4 p = img.pixel(img.width / 2, img.height / 2) * 255.0f;
    for (int c = 0; c < 3; ++c) {
      const double expected = srgb ? srgbByHand(kLinear[c]) : 255.0 * kLinear[c];
      EXPECT_NEAR(p[c], expected, 1.0) << what << " view " << v << " channel " << c;
    }
  }
}

TEST(ColorEncoding, EveryBackEndWritesSrgbUnlessLinear) {
  const fs::path scene = planeScene(false);
  const fs::path out = test::freshDir("color_out");
  for (const std::string backend : {"svr", "svr-layered", "deferred", "mvr --pst quad", "mvr --pst strip",
                                    "mvr --pst exact", "mvr --pst cpu", "interp --acquire dual"}) {
    for (const bool linear : {false, true}) {
      fs::remove_all(out);
      const std::string args = "render " + scene.string() + " --backend " + backend +
                               " --views 3 --size 40x30" + (linear ? " --linear" : "");
      const auto r = test::runMvr(args + " --out " + out.string());
      ASSERT_TRUE(test::succeeded(r)) << args;
      expectCentres(out, !linear, args);
    }
  }
}

TEST(ColorEncoding, AccumulatedPassesAndFloatFilesAreEncodedToo) {
  const fs::path out = test::freshDir("color_passes");
  for (const std::string flags : {"--backend mvr --pst strip", "--backend mvr --pst exact",
                                  "--backend mvr --pst cpu", "--backend svr --bits 16",
                                  "--backend mvr --pst cpu --format tiff"}) {
    fs::remove_all(out);
    const std::string args = "render " + planeScene(true).string() + " " + flags + " --views 3 --size 40x30";
    const auto r = test::runMvr(args + " --out " + out.string());
    ASSERT_TRUE(test::succeeded(r)) << args;
    expectCentres(out, true, args);
  }
}

// A texture file is sRGB-encoded: an unlit, white, textured plane seen head
// on writes the texture's own bytes back (GL decodes sRGB textures before
// filtering, the CPU samplers decode the same way), and its linear values
// with --linear. Byte 128 is linear 0.2158 (55.0 of 255).
TEST(ColorEncoding, TexturesAreDecodedFromSrgb) {
  const fs::path dir = test::freshDir("color_texture");
  fs::create_directories(dir);
  Image grey(8, 8, PixelType::Srgb8);
  for (uint8_t& b : grey.bytes) b = 128;
  writeImage(grey, (dir / "grey.png").string());
  std::ofstream(dir / "plane.json") << R"({"meshes": [{"file": ")" << test::assetsDir() << R"(/plane.obj",
      "material": {"diffuse": [1, 1, 1], "texture": "grey.png"}}],
    "lights": [], "ambient": [1, 1, 1],
    "camera": {"distance": 4, "image_plane": 2.0, "track": [-0.5, 0.5], "near": 2, "far": 6}})";
  const fs::path out = dir / "out";
  for (const std::string backend : {"svr", "deferred", "mvr --pst strip", "mvr --pst exact --texture direct",
                                    "mvr --pst cpu"}) {
    for (const bool linear : {false, true}) {
      fs::remove_all(out);
      const std::string args = "render " + (dir / "plane.json").string() + " --backend " + backend +
                               " --views 3 --size 40x30" + (linear ? " --linear" : "");
      const auto r = test::runMvr(args + " --out " + out.string());
      ASSERT_TRUE(test::succeeded(r)) << args;
      const Image img = readImage((out / "view_0001.png").string());
      EXPECT_NEAR(img.pixel(20, 15).g * 255.0f, linear ? 55.0f : 128.0f, 1.0f) << args;
    }
  }
}

TEST(ColorEncoding, ExrIsLinear) {
  const fs::path out = test::freshDir("color_exr");
  ASSERT_TRUE(test::succeeded(test::runMvr("render " + planeScene(false).string() +
                         " --format exr --views 2 --size 40x30 --out " + out.string())));
  const Image img = readImage((out / "view_0000.exr").string());
  EXPECT_NEAR(img.pixel(20, 15).g, 0.2f, 1e-5f);
  EXPECT_EQ(Manifest::read(out.string()).colorEncoding(), "linear");
}

}  // namespace
}  // namespace mvr
