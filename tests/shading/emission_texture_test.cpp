// Emission textures (glTF's emissiveTexture) and unlit materials
// (KHR_materials_unlit), per texel in every back end. A pixel is
//   lit diffuse x T + E x G   (G: the emission texture's texel, 1 without)
// and an unlit material's lit diffuse is its albedo, whatever the lights.
// Each quad's halves glow differently, so that the emission texture's mean
// (what was drawn before) misses both by far.
#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>

#include "mvr/images/image_file.h"
#include "mvr/assets/scene_io.h"
#include "shading/shading_plan.h"
#include "shading/texture_set.h"
#include "tests/support/meshes.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;

// An 8 x 8 sRGB texture, its left half `left` and right half `right`
// (linear colours); returns its path.
std::string halvesPng(const std::string& name, glm::vec3 left, glm::vec3 right) {
  const fs::path dir = fs::temp_directory_path() / ("mvr_emission_test_" + std::to_string(getpid()));
  fs::create_directories(dir);
  Image img(8, 8, PixelType::Srgb8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) img.setLinear(x, y, glm::vec4(x < 4 ? left : right, 1.0f));
  const std::string path = (dir / (name + ".png")).string();
  writeImage(img, path);
  return path;
}

// Four unit quads in a row, lit head on by 0.5:
//   0  textured, its emission textured too;
//   1  untextured, its emission textured;
//   2  unlit and textured;
//   3  untextured with a plain emission (the path without a texture).
Scene glowingQuads() {
  Scene s;
  Material textured;
  textured.diffuse = glm::vec3(0.6f);
  textured.texture = halvesPng("base", glm::vec3(1.0f, 0.5f, 0.25f), glm::vec3(0.25f, 0.5f, 1.0f));
  textured.emission = glm::vec3(0.5f);
  textured.emissionTexture = halvesPng("glow", glm::vec3(0.8f, 0.0f, 0.0f), glm::vec3(0.0f, 0.0f, 0.8f));
  Material plain;
  plain.diffuse = glm::vec3(0.2f, 0.4f, 0.2f);
  plain.emission = glm::vec3(1.0f, 0.5f, 1.0f);
  plain.emissionTexture = halvesPng("glow2", glm::vec3(0.0f, 0.6f, 0.0f), glm::vec3(0.4f, 0.4f, 0.0f));
  Material unlit;
  unlit.unlit = true;
  unlit.diffuse = glm::vec3(0.9f);
  unlit.texture = halvesPng("unlit", glm::vec3(0.2f, 0.9f, 0.6f), glm::vec3(0.7f, 0.1f, 0.3f));
  Material constant;
  constant.diffuse = glm::vec3(0.5f);
  constant.emission = glm::vec3(0.1f, 0.2f, 0.3f);
  s.materials = {textured, plain, unlit, constant};
  for (uint32_t q = 0; q < 4; ++q) test::addQuad(s, glm::vec3(float(q) * 1.2f, 0.0f, 0.0f), glm::vec2(1.0f), q);
  s.lights = {Light{Light::Type::Directional, glm::vec3(0, 0, -1), glm::vec3(0.5f)}};
  s.ambient = glm::vec3(0.0f);
  return s;
}

// The texel of a halves texture at the middle of its left or right half.
glm::vec3 half(const std::string& path, bool right) {
  return glm::vec3(readImage(path).linear(right ? 6 : 1, 4));
}

class EmissionTexture : public test::GlTest {};

TEST_F(EmissionTexture, EachTexelGlowsAndUnlitIgnoresTheLightsInEveryBackEnd) {
  const Scene scene = glowingQuads();
  const shading::ShadingPlan plan = shading::planShading(scene);
  EXPECT_TRUE(plan.emissionTexture);
  EXPECT_EQ(plan.passNames(), "diffuse+texture");  // no pass for the glow
  const ShearingCamera cam(cameraFor(scene, 192, 48), 192, 48, 3);
  auto svr = makeSvrRenderer(scene, PixelType::U8);
  const test::CaptureSink reference = test::renderViews(*svr, cam);
  const Image& centre = reference.views.at({0, 1});
  for (int q = 0; q < 4; ++q)
    for (bool right : {false, true}) {
      const Material& m = scene.materials[size_t(q)];
      const glm::vec3 t = m.texture.empty() ? glm::vec3(1.0f) : half(m.texture, right);
      const glm::vec3 g = m.emissionTexture.empty() ? glm::vec3(1.0f) : half(m.emissionTexture, right);
      const glm::vec3 expected = (m.unlit ? 1.0f : 0.5f) * m.diffuse * t + m.emission * g;
      const glm::vec3 at = cam.project(glm::dvec3(float(q) * 1.2f + (right ? 0.8f : 0.2f), 0.5f, 0.0f), 1);
      const glm::vec4 got = centre.linear(int(at.x), int(at.y));
      EXPECT_NEAR(glm::distance(glm::vec3(got), expected), 0.0f, 0.02f) << "quad " << q << (right ? " right" : " left");
    }
  const test::BackEndsAgainstSvr all = test::compareBackEndsWithSvr(scene, cam);
  for (const auto& [name, d] : all.difference) {
    std::printf("%s: min PSNR %.2f dB\n", name.c_str(), d.minPsnr);
    EXPECT_GE(d.minPsnr, 35.0) << name;
  }
  struct Path {
    TextureMode texture;
    PstBuilder builder;
    const char* name;
  };
  for (const Path& p : {Path{TextureMode::Direct, PstBuilder::Cpu, "direct"},
                        Path{TextureMode::Vector, PstBuilder::Cpu, "vector"},
                        Path{TextureMode::Vector, PstBuilder::Gpu, "vector, gpu-built"}}) {
    auto mvr = makeMvrRenderer(scene, PstMode::Exact, PixelType::U8, p.texture, p.builder);
    const double psnr = test::compareViews(reference, test::renderViews(*mvr, cam)).minPsnr;
    std::printf("exact %s: min PSNR %.2f dB\n", p.name, psnr);
    EXPECT_GE(psnr, 30.0) << p.name;
  }
  // The image-based back end's source layers peel by geometry passes
  // (their fragment lists keep no emission).
  test::expectCloseToSvr(reference, test::renderSpec("interp", scene, cam), "interp", 35.0);
}

// The white texture a glow-only material gets is one layer of one texel,
// and the emission texture its own layer.
TEST(EmissionTextureSet, AGlowOnlyMaterialGetsAWhiteBase) {
  const Scene scene = glowingQuads();
  const shading::TextureSet set = shading::TextureSet::load(scene);
  const std::vector<int>& base = set.materialLayers();
  const std::vector<int>& glow = set.emissionLayers();
  ASSERT_EQ(base.size(), 4u);
  EXPECT_GE(glow[0], 0);
  EXPECT_GE(glow[1], 0);
  EXPECT_EQ(glow[2], -1);
  EXPECT_EQ(glow[3], -1);
  ASSERT_GE(base[1], 0);
  EXPECT_EQ(set.size(base[1]), glm::ivec2(1));
  EXPECT_EQ(set.sample(base[1], glm::vec2(0.3f), 0.0f), glm::vec4(1.0f));
  EXPECT_EQ(base[3], -1);
}

}  // namespace
}  // namespace mvr
