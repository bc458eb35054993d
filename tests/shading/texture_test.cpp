// Textures: the shared MIP chain, Halle's 1-D texture vectors, and MVR's
// texture pass against SVR's mipmapped texturing. Tolerances (PSNR per
// view against svr, on assets/textured.json, a high-contrast checker):
//  cpu           >= 40 dB: exact uv; level of detail from the horizontal
//                footprint only, and our trilinear arithmetic, not GL's.
//  exact direct  >= 40 dB: the same in a fragment shader.
//  exact vector  >= 26 dB: the vector is filtered twice (2D at extraction,
//                1-D per view), which blurs the checker's one-texel lines.
// Minification must not shimmer: the vector path's per-view PSNR varies by
// under 3 dB across the track.
#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "mvr/error.h"
#include "mvr/images/image_file.h"
#include "mvr/assets/scene_io.h"
#include "shading/shading_plan.h"
#include "shading/texture_set.h"
#include "shading/texture_vector.h"
#include "tests/support/meshes.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;

// A scene with one material textured by a w x h image made by fill(x, y).
template <class Fill>
Scene texturedScene(const std::string& name, int w, int h, Fill fill) {
  const fs::path dir = fs::temp_directory_path() / ("mvr_texture_test_" + std::to_string(getpid()));
  fs::create_directories(dir);
  Image img(w, h, PixelType::U8);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const glm::vec3 c = fill(x, y);
      uint8_t* p = img.row(y) + x * 4;
      for (int k = 0; k < 3; ++k) p[k] = uint8_t(std::lrint(c[k] * 255));
      p[3] = 255;
    }
  const std::string path = (dir / (name + ".png")).string();
  writeImage(img, path);
  Scene s;
  Material m;
  m.texture = path;
  s.materials = {m};
  return s;
}

TEST(TextureSet, ChainHalvesToOneTexelAndSamplesTexelCentres) {
  Scene s = texturedScene("ramp", 8, 4, [](int x, int y) { return glm::vec3(x / 7.0f, y / 3.0f, 0.5f); });
  shading::TextureSet t = shading::TextureSet::load(s);
  ASSERT_FALSE(t.empty());
  EXPECT_EQ(t.levels(0), 4);  // 8x4, 4x2, 2x1, 1x1
  // Texel (3, 0) of the bottom row (v = 0 is the image's last row, y = 3).
  const glm::vec4 c = t.sample(0, glm::vec2(3.5f / 8, 0.5f / 4), 0.0f);
  EXPECT_NEAR(c.r, 3 / 7.0f, 1.0f / 255);
  EXPECT_NEAR(c.g, 1.0f, 1.0f / 255);
  // Repeat: u + 1 is the same texel; the 1x1 level is the mean.
  EXPECT_EQ(t.sample(0, glm::vec2(1 + 3.5f / 8, 0.5f / 4), 0.0f), c);
  EXPECT_NEAR(t.sample(0, glm::vec2(0.3f, 0.6f), 3.0f).r, 0.5f, 2.0f / 255);
  EXPECT_NEAR(t.lodFor(0, glm::vec2(4.0f / 8, 0.0f)), 2.0f, 1e-6f);
}

TEST(TextureSet, MissingFileIsAnErrorNamingIt) {
  Scene s;
  Material m;
  m.texture = "/nonexistent/brick.png";
  s.materials = {m};
  try {
    shading::TextureSet::load(s);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("brick.png"), std::string::npos) << e.what();
  }
}

TEST(TextureVectors, PowerOfTwoLengthsAndAChainThatAverages) {
  EXPECT_EQ(shading::TextureVectors::lengthFor(0.2f), 1);
  EXPECT_EQ(shading::TextureVectors::lengthFor(5.0f), 8);
  EXPECT_EQ(shading::TextureVectors::lengthFor(1e9f), shading::TextureVectors::kMaxLength);
  Scene s = texturedScene("stripes", 16, 1, [](int x, int) { return glm::vec3(x / 15.0f); });
  shading::TextureSet t = shading::TextureSet::load(s);
  shading::TextureVectors v;
  // A slice across the whole texture, no perspective (1/w = 1 at both ends).
  const int base = v.add(t, 0, glm::vec2(0, 0.5f), glm::vec2(1, 0.5f), 1.0f, 1.0f, 16.0f);
  EXPECT_EQ(base, 0);
  EXPECT_EQ(v.texels().size(), 31u);  // 16 + 8 + 4 + 2 + 1
  EXPECT_NEAR(v.texels()[5].r, 5 / 15.0f, 1.0f / 255);
  EXPECT_NEAR(v.texels()[16].r, 0.5f * (v.texels()[0].r + v.texels()[1].r), 1e-6f);
  EXPECT_NEAR(v.texels()[30].r, 0.5f, 1.0f / 255);
  // One texel per pixel reads level 0; four per pixel reads level 2.
  EXPECT_NEAR(v.sample(base, 16, 5.5f / 16, 1.0f).r, v.texels()[5].r, 1e-6f);
  EXPECT_NEAR(v.sample(base, 16, 1.5f / 4, 4.0f).r, v.texels()[16 + 8 + 1].r, 1e-6f);
}

TEST(TextureVectors, GivenTexelsGetTheSameChainAndCopiesKeepIt) {
  shading::TextureVectors v, w;
  const std::vector<glm::vec4> four = {glm::vec4(0.0f), glm::vec4(0.2f), glm::vec4(0.4f), glm::vec4(1.0f)};
  w.addTexels(std::vector<glm::vec4>{glm::vec4(0.5f)});  // one texel: no chain
  EXPECT_EQ(w.texels().size(), 1u);
  const int base = v.addTexels(four);
  ASSERT_EQ(v.texels().size(), 7u);  // 4 + 2 + 1
  EXPECT_FLOAT_EQ(v.texels()[4].r, 0.1f);
  EXPECT_FLOAT_EQ(v.texels()[5].r, 0.7f);
  EXPECT_FLOAT_EQ(v.texels()[6].r, 0.4f);
  const int copy = w.append(v, base, 4);
  EXPECT_EQ(copy, 1);
  EXPECT_FLOAT_EQ(w.sample(copy, 4, 2.5f / 4, 1.0f).r, 0.4f);  // texel 2's centre
  EXPECT_FLOAT_EQ(w.sample(copy, 4, 0.5f, 2.0f).r, 0.4f);      // level 1, between its texels
  EXPECT_THROW(v.addTexels(std::vector<glm::vec4>(3)), Error);
  EXPECT_THROW(v.addTexels({}), Error);
}

TEST(TextureVectors, PerspectiveIsCorrectedAtExtraction) {
  // uv runs 0..1 while 1/w runs 1..1/3: screen u = 1/2 is uv = 1/4.
  Scene s = texturedScene("ramp16", 16, 1, [](int x, int) { return glm::vec3(x / 15.0f); });
  shading::TextureSet t = shading::TextureSet::load(s);
  shading::TextureVectors v;
  v.add(t, 0, glm::vec2(0, 0.5f), glm::vec2(1.0f / 3, 0.5f / 3), 1.0f, 1.0f / 3, 64.0f);
  const float uv = (0.5f * (1.0f / 3)) / (0.5f * (1 + 1.0f / 3));
  EXPECT_NEAR(uv, 0.25f, 1e-6f);
  const float expect = t.sample(0, glm::vec2(uv, 0.5f), 0.0f).r;
  EXPECT_NEAR(0.5f * (v.texels()[31].r + v.texels()[32].r), expect, 0.02f);
}

// Nine quads in a row, each with a one-colour texture of its own size
// (nine sizes: one more than the GL groups), lit head on.
Scene quadsOfNineSizes() {
  static const glm::ivec2 kSizes[9] = {{32, 32}, {16, 4}, {8, 8}, {2, 4}, {16, 16}, {4, 4}, {8, 2}, {4, 2}, {2, 2}};
  const fs::path dir = fs::temp_directory_path() / ("mvr_texture_test_" + std::to_string(getpid()));
  fs::create_directories(dir);
  Scene s;
  for (int q = 0; q < 9; ++q) {
    const glm::vec3 colour(float(q % 3) / 2.0f, float(q / 3) / 2.0f, q == 4 ? 0.0f : 1.0f);
    Image img(kSizes[q].x, kSizes[q].y, PixelType::U8);
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        for (int k = 0; k < 4; ++k) img.row(y)[x * 4 + k] = uint8_t(k == 3 ? 255 : std::lrint(colour[k] * 255));
    Material m;
    m.diffuse = glm::vec3(1.0f);
    m.texture = (dir / ("size" + std::to_string(q) + ".png")).string();
    writeImage(img, m.texture);
    s.materials.push_back(m);
    test::addQuad(s, glm::vec3(float(q) * 1.2f, 0.0f, 0.0f), glm::vec2(1.0f), uint32_t(q));
  }
  s.lights = {Light{Light::Type::Directional, glm::vec3(0, 0, -1), glm::vec3(1.0f)}};
  s.ambient = glm::vec3(0.0f);
  return s;
}

// Each texture keeps its size: no resampling to the largest, except the
// two smallest of nine sizes, which share the eighth group.
TEST(TextureSet, TexturesKeepTheirOwnSizes) {
  const Scene s = quadsOfNineSizes();
  const shading::TextureSet t = shading::TextureSet::load(s);
  for (int layer : {0, 1, 2, 3, 4, 5, 6}) EXPECT_EQ(t.size(layer), glm::ivec2(readImage(s.materials[size_t(layer)].texture).width,
                                                                                readImage(s.materials[size_t(layer)].texture).height)) << layer;
  EXPECT_EQ(t.size(7), glm::ivec2(4, 2));  // 4 x 2 and 2 x 2 share one group of 4 x 2
  EXPECT_EQ(t.size(8), glm::ivec2(4, 2));
  EXPECT_EQ(t.levels(0), 6);  // 32 .. 1
  EXPECT_EQ(t.levels(1), 5);  // 16 x 4 .. 1 x 1
  const std::vector<glm::ivec2> slots = t.materialSlots();
  EXPECT_EQ(slots[7], glm::ivec2(7, 0));
  EXPECT_EQ(slots[8], glm::ivec2(7, 1));
  EXPECT_NEAR(t.sample(4, glm::vec2(0.3f, 0.7f), 0.0f).r, 0.5f, 2.0f / 255);  // quad 4: (0.5, 0.5, 0)
}

class TextureVsSvr : public test::GlTest {};

// Every back end finds each quad's texture among the GL groups: svr's
// middle of each quad has its colour, and every path agrees with svr.
TEST_F(TextureVsSvr, TexturesOfManySizesInEveryBackEnd) {
  const Scene scene = quadsOfNineSizes();
  const ShearingCamera cam(cameraFor(scene, 216, 32), 216, 32, 3);
  auto svr = makeSvrRenderer(scene, PixelType::U8);
  const test::CaptureSink reference = test::renderViews(*svr, cam);
  const Image& centre = reference.views.at({0, 1});
  for (int q = 0; q < 9; ++q) {
    const glm::vec3 expected(readImage(scene.materials[size_t(q)].texture).linear(0, 0));
    const glm::vec3 at = cam.project(glm::dvec3(float(q) * 1.2f + 0.5f, 0.5f, 0.0f), 1);
    const glm::vec4 got = centre.linear(int(at.x), int(at.y));
    EXPECT_NEAR(glm::distance(glm::vec3(got), expected), 0.0f, 0.02f) << "quad " << q;
  }
  const test::BackEndsAgainstSvr all = test::compareBackEndsWithSvr(scene, cam);
  for (const auto& [name, d] : all.difference) EXPECT_GE(d.minPsnr, 35.0) << name;
  for (TextureMode mode : {TextureMode::Direct, TextureMode::Vector}) {
    auto mvr = makeMvrRenderer(scene, PstMode::Exact, PixelType::U8, mode);
    EXPECT_GE(test::compareViews(reference, test::renderViews(*mvr, cam)).minPsnr, 30.0)
        << (mode == TextureMode::Vector ? "vector" : "direct");
  }
}

// Emission is added after the lighting and the texture, undimmed by
// either: at each quad's middle, head-on light 0.5, svr shows 0.5 T + E
// (T: the texture's colour, 1 for the untextured quad 4), and every back
// end agrees with svr. The MVR passes carry it in the lit colour and give
// back in the texture pass what its multiply took (two-source blending on
// the GL paths): no pass is added.
TEST_F(TextureVsSvr, EmissionIsAddedAfterTheTextureInEveryBackEnd) {
  Scene scene = quadsOfNineSizes();
  scene.lights[0].color = glm::vec3(0.5f);
  for (size_t q = 1; q < 9; q += 2) scene.materials[q].emission = glm::vec3(0.3f, 0.2f, 0.1f);
  scene.materials[4].texture.clear();
  scene.materials[4].diffuse = glm::vec3(0.4f, 0.8f, 0.2f);
  scene.materials[4].emission = glm::vec3(0.1f, 0.0f, 0.5f);
  const ShearingCamera cam(cameraFor(scene, 216, 32), 216, 32, 3);
  auto svr = makeSvrRenderer(scene, PixelType::U8);
  const test::CaptureSink reference = test::renderViews(*svr, cam);
  const Image& centre = reference.views.at({0, 1});
  for (int q = 0; q < 9; ++q) {
    const Material& m = scene.materials[size_t(q)];
    const glm::vec3 texel = m.texture.empty() ? glm::vec3(1.0f) : glm::vec3(readImage(m.texture).linear(0, 0));
    const glm::vec3 expected = 0.5f * m.diffuse * texel + m.emission;
    const glm::vec3 at = cam.project(glm::dvec3(float(q) * 1.2f + 0.5f, 0.5f, 0.0f), 1);
    const glm::vec4 got = centre.linear(int(at.x), int(at.y));
    EXPECT_NEAR(glm::distance(glm::vec3(got), expected), 0.0f, 0.02f) << "quad " << q;
  }
  const test::BackEndsAgainstSvr all = test::compareBackEndsWithSvr(scene, cam);
  for (const auto& [name, d] : all.difference) EXPECT_GE(d.minPsnr, 35.0) << name;
  for (const auto& [name, passes] : all.passes) EXPECT_EQ(passes, "diffuse+texture") << name;
  for (TextureMode mode : {TextureMode::Direct, TextureMode::Vector}) {
    auto mvr = makeMvrRenderer(scene, PstMode::Exact, PixelType::U8, mode);
    EXPECT_GE(test::compareViews(reference, test::renderViews(*mvr, cam)).minPsnr, 30.0)
        << (mode == TextureMode::Vector ? "vector" : "direct");
  }
  // After MVR's two-source blending, another renderer in the same context
  // draws into two targets (deferred's G-buffer): the blend must be off.
  auto deferred = makeDeferredRenderer(scene, PixelType::U8);
  EXPECT_GE(test::compareViews(reference, test::renderViews(*deferred, cam)).minPsnr, 35.0);
}

std::vector<double> perViewPsnr(const test::CaptureSink& a, const test::CaptureSink& b) {
  std::vector<double> out;
  for (const auto& [key, img] : a.views) out.push_back(compareImages(img, b.views.at(key)).psnr);
  return out;
}

TEST_F(TextureVsSvr, EveryPathIsCloseToSvrWithoutShimmer) {
  Scene scene = loadScene(test::assetPath("textured.json"));
  ShearingCamera cam(*scene.camera, 160, 120, 7);
  auto svr = makeSvrRenderer(scene, PixelType::U8);
  const test::CaptureSink reference = test::renderViews(*svr, cam);
  auto deferred = makeDeferredRenderer(scene, PixelType::U8);
  EXPECT_GE(test::compareViews(reference, test::renderViews(*deferred, cam)).minPsnr, 40.0);
  struct Case {
    PstMode mode;
    TextureMode texture;
    double minPsnr;
  };
  for (Case c : {Case{PstMode::Cpu, TextureMode::Direct, 40.0},
                 Case{PstMode::Exact, TextureMode::Direct, 40.0},
                 Case{PstMode::Exact, TextureMode::Vector, 26.0}}) {
    auto mvr = makeMvrRenderer(scene, c.mode, PixelType::U8, c.texture);
    RenderStats stats;
    const test::CaptureSink views = test::renderViews(*mvr, cam, stats);
    EXPECT_EQ(stats.notes["passes"], "diffuse+texture+view-dependent");
    const std::vector<double> psnr = perViewPsnr(reference, views);
    const auto [lo, hi] = std::minmax_element(psnr.begin(), psnr.end());
    const std::string name = std::string(pstModeName(c.mode)) + (c.texture == TextureMode::Vector ? " vector" : " direct");
    EXPECT_GE(*lo, c.minPsnr) << name;
    // Shimmer would show as views whose error jumps when the level of
    // detail flips; the vector path's error must be even across views.
    if (c.texture == TextureMode::Vector) {
      EXPECT_LT(*hi - *lo, 3.0) << name;
    }
  }
}

TEST_F(TextureVsSvr, ATextureAddsExactlyOnePass) {
  Scene scene = loadScene(test::assetPath("textured.json"));
  for (Material& m : scene.materials) m.specular = glm::vec3(0);
  EXPECT_EQ(shading::planShading(scene).passNames(), "diffuse+texture");
  ShearingCamera cam(*scene.camera, 64, 48, 3);
  auto mvr = makeMvrRenderer(scene, PstMode::Strip, PixelType::U8);
  RenderStats stats;
  NullSink sink;
  mvr->render(cam, sink, stats);
  EXPECT_EQ(stats.counters["passes"], 2.0);
  EXPECT_GT(stats.counters["texture_vector_texels"], 0.0);
  for (Material& m : scene.materials) m.texture.clear();
  auto plain = makeMvrRenderer(scene, PstMode::Strip, PixelType::U8);
  RenderStats plainStats;
  plain->render(cam, sink, plainStats);
  EXPECT_EQ(plainStats.counters["passes"], 1.0);
  EXPECT_EQ(plainStats.notes["passes"], "diffuse");
}

}  // namespace
}  // namespace mvr
