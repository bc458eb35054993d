// The image-based light (shading/image_light.h) against what can be
// worked by hand: a constant surround (the white furnace), a map linear in
// the direction (its mirror level is the map, its irradiance is the
// cosine lobe's 2/3 of the linear part), the prefiltered levels against
// brute-force integration of the GGX lobe, the map's rotation and
// Scene::transform, and MVR against SVR with the environment lighting a
// metallic-roughness scene.
#include <cmath>
#include <fstream>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include "mvr/assets/scene_io.h"
#include "mvr/image.h"
#include "shading/brdf.h"
#include "shading/image_light.h"
#include "shading/lighting.h"
#include "shading/shading_plan.h"
#include "tests/support/cli.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

using shading::ImageLight;

// An equirectangular map of radiance f(direction), in the axes ImageLight reads.
template <class F>
Image equirect(int width, F f) {
  Image img(width, width / 2, PixelType::F32);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < width; ++x) {
      const double phi = (2.0 * (x + 0.5) / width - 1.0) * M_PI, lat = (0.5 - (y + 0.5) / img.height) * M_PI;
      const glm::vec3 d(std::cos(lat) * std::cos(phi), std::sin(lat), std::cos(lat) * std::sin(phi));
      img.setLinear(x, y, glm::vec4(f(d), 1.0f));
    }
  return img;
}

std::vector<glm::vec3> someDirections() {
  std::vector<glm::vec3> out;
  for (int i = 0; i < 40; ++i) {  // a spiral over the sphere, and the axes
    const float z = 1.0f - (i + 0.5f) / 20.0f, a = 2.39996f * float(i), r = std::sqrt(1.0f - z * z);
    out.push_back({r * std::cos(a), r * std::sin(a), z});
  }
  for (glm::vec3 axis : {glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)}) out.push_back(axis), out.push_back(-axis);
  return out;
}

TEST(ImageLight, AConstantSurroundIsAWhiteFurnace) {
  const ImageLight light(equirect(64, [](glm::vec3) { return glm::vec3(0.7f, 0.5f, 0.25f); }));
  for (const glm::vec3& d : someDirections()) {
    EXPECT_NEAR(light.irradiance(d).r, 0.7f, 1e-3f);
    EXPECT_NEAR(light.irradiance(d).b, 0.25f, 1e-3f);
    for (float roughness : {0.0f, 0.1f, 0.3f, 0.6f, 1.0f}) EXPECT_NEAR(light.radiance(d, roughness).g, 0.5f, 1e-4f);
  }
}

TEST(ImageLight, ALinearMapsMirrorIsTheMapAndItsIrradianceTheCosineLobes) {
  // L(d) = 0.5 + 0.4 d: the mirror level gives L back; E(n) / pi of the
  // linear part is 2/3 of it (the cosine lobe's first band).
  const auto map = [](glm::vec3 d) { return glm::vec3(0.5f) + 0.4f * d; };
  const ImageLight light(equirect(512, map));
  for (const glm::vec3& d : someDirections()) {
    const glm::vec3 mirror = light.levelRadiance(d, 0), e = light.irradiance(d);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(mirror[c], map(d)[c], 4e-3f) << d.x << " " << d.y << " " << d.z;
      EXPECT_NEAR(e[c], 0.5f + 0.4f * (2.0f / 3.0f) * d[c], 3e-3f);
    }
  }
}

// The prefiltered radiance round r by definition: L weighted by the GGX
// lobe's D(n.h) (n.l) with n = v = r, over the sphere by quadrature.
glm::vec3 bruteForce(const std::function<glm::vec3(glm::vec3)>& map, const glm::vec3& r, float roughness) {
  const float alpha = roughness * roughness;
  glm::dvec3 sum(0.0);
  double weight = 0.0;
  constexpr int kRows = 1024;
  for (int i = 0; i < kRows; ++i) {
    const double theta = (i + 0.5) / kRows * M_PI;
    for (int j = 0; j < 2 * kRows; ++j) {
      const double phi = (j + 0.5) / kRows * M_PI;
      const glm::vec3 l(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      const float nl = glm::dot(r, l);
      if (nl <= 0.0f) continue;
      const glm::vec3 h = glm::normalize(l + r);
      const double w = shading::ggxDistribution(alpha, glm::dot(r, h)) * nl * std::sin(theta);
      sum += glm::dvec3(map(l)) * w;
      weight += w;
    }
  }
  return glm::vec3(sum / weight);
}

TEST(ImageLight, PrefilteredLevelsMatchBruteForceIntegration) {
  // A sky with a soft sun: varied enough that each level's blur shows.
  const glm::vec3 sun = glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f));
  const std::function<glm::vec3(glm::vec3)> map = [&](glm::vec3 d) {
    return glm::vec3(0.2f + 0.3f * std::max(d.y, 0.0f)) + glm::vec3(4.0f) * std::pow(std::max(glm::dot(d, sun), 0.0f), 16.0f);
  };
  const ImageLight light(equirect(1024, map));
  const glm::vec3 directions[] = {sun, glm::normalize(sun + glm::vec3(0.3f, -0.2f, 0.1f)), glm::vec3(0, 1, 0),
                                  glm::normalize(glm::vec3(-1, 0.2f, 0.4f))};
  for (int k = 2; k < ImageLight::kLevels; ++k)
    for (const glm::vec3& r : directions) {
      const glm::vec3 want = bruteForce(map, r, ImageLight::levelRoughness(k));
      const glm::vec3 got = light.levelRadiance(r, k);
      EXPECT_NEAR(got.r, want.r, 0.03f * want.r + 0.005f) << "level " << k;
    }
}

TEST(ImageLight, BadTexelsAreBroughtIntoRange) {
  // A NaN, an infinity and a negative texel in a constant sky of 0.5: the
  // first and last read as 0, the infinity as half float's largest; the
  // harmonics stay finite and near the rest's.
  Image map = equirect(64, [](glm::vec3) { return glm::vec3(0.5f); });
  map.setLinear(3, 5, glm::vec4(std::nanf(""), 0.5f, 0.5f, 1.0f));
  map.setLinear(10, 20, glm::vec4(-1.0f, 0.5f, 0.5f, 1.0f));
  map.setLinear(40, 1, glm::vec4(0.5f, std::numeric_limits<float>::infinity(), 0.5f, 1.0f));
  const ImageLight light(map);
  EXPECT_EQ(light.changedTexels(), 3u);
  for (const glm::vec3& d : someDirections()) {
    EXPECT_NEAR(light.irradiance(d).r, 0.5f, 0.01f);
    EXPECT_TRUE(std::isfinite(light.irradiance(d).g));
    EXPECT_TRUE(std::isfinite(light.radiance(d, 0.5f).g));
  }
  // The smallest map there is, 2 x 1, still lights.
  Image tiny(2, 1, PixelType::F32);
  tiny.setLinear(0, 0, glm::vec4(1.0f));
  tiny.setLinear(1, 0, glm::vec4(1.0f));
  EXPECT_NEAR(ImageLight(tiny).irradiance(glm::vec3(0, 0, 1)).r, 1.0f, 1e-3f);
}

TEST(ImageLight, ReadsARadianceHdrFile) {
  // Radiance's RGBE, written flat (no run-length coding) by hand: 16 x 8
  // texels of mantissas 128, 64, 255 at exponent 128: m / 256, (0.5, 0.25,
  // 0.996), give or take the half step some readers add.
  const std::filesystem::path file = test::freshDir("image_light_hdr") / "grey.hdr";
  std::filesystem::create_directories(file.parent_path());
  {
    std::ofstream out(file, std::ios::binary);
    out << "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8 +X 16\n";
    for (int i = 0; i < 16 * 8; ++i) out << char(128) << char(64) << char(255) << char(128);
  }
  const std::shared_ptr<const ImageLight> light = ImageLight::load(file.string());
  const glm::vec3 e = light->irradiance(glm::vec3(0, 1, 0));
  EXPECT_NEAR(e.r, 0.5f, 0.005f);
  EXPECT_NEAR(e.g, 0.25f, 0.005f);
  EXPECT_NEAR(e.b, 0.996f, 0.005f);
  EXPECT_THROW(ImageLight::load((file.parent_path() / "none.hdr").string()), Error);
}

Scene furnaceScene(const Image& map) {
  Scene s = loadScene(test::assetPath("metal_rough.json"));
  s.lights.clear();
  s.ambient = glm::vec3(0.0f);
  s.environment = Environment{"map"};
  s.environment->light = std::make_shared<const ImageLight>(map);
  return s;
}

TEST(ImageLight, TheRotationAndTheScenesTransformTurnTheMap) {
  Scene s = furnaceScene(equirect(256, [](glm::vec3 d) { return glm::vec3(0.5f) + 0.4f * d; }));
  // Turned +90 degrees about +y, the map's +x (brightest red) faces -z.
  s.environment->turn(90.0f);
  EXPECT_NEAR(shading::environmentDiffuse(s, glm::vec3(0, 0, -1)).r, 0.5f + 0.4f * 2.0f / 3.0f, 3e-3f);
  EXPECT_NEAR(shading::environmentDiffuse(s, glm::vec3(1, 0, 0)).r, 0.5f, 3e-3f);
  // The scene turned with its lights: the map turns with it.
  const glm::vec3 before = shading::environmentDiffuse(s, glm::vec3(0, 0, -1));
  const glm::mat4 turn = glm::rotate(glm::mat4(1.0f), 0.7f, glm::vec3(0.2f, 1.0f, -0.3f)) * glm::scale(glm::mat4(1.0f), glm::vec3(3.0f));
  s.transform(turn);
  const glm::vec3 after = shading::environmentDiffuse(s, glm::normalize(glm::vec3(turn * glm::vec4(0, 0, -1, 0))));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(after[c], before[c], 1e-5f);
}

TEST(ImageLight, TheEnvironmentJoinsThePlanAndTheDiffuse) {
  Scene s = furnaceScene(equirect(64, [](glm::vec3) { return glm::vec3(1.0f); }));
  const shading::ShadingPlan plan = shading::planShading(s);
  EXPECT_TRUE(plan.environment);
  EXPECT_NE(plan.glslDefines().find("#define ENVIRONMENT"), std::string::npos);
  // The white furnace: a white Lambert surface sends back the surround's 1
  // whichever way it faces.
  for (const glm::vec3& n : someDirections())
    EXPECT_NEAR(shading::diffuse(s, glm::vec3(1.0f), glm::vec3(0.0f), n).g, 1.0f, 1e-3f);
  s.environment.reset();
  EXPECT_FALSE(shading::planShading(s).environment);
}

class ImageLightRender : public test::GlTest {};

TEST_F(ImageLightRender, AWhiteFurnaceLightsADiffuseSphereEvenly) {
  // Lambert albedo 0.6 under a constant surround of 1 and nothing else:
  // every pixel the cup covers is 0.6, whatever its normal, in svr and mvr.
  Scene s = furnaceScene(equirect(64, [](glm::vec3) { return glm::vec3(1.0f); }));
  for (Material& m : s.materials) m = Material{}, m.diffuse = glm::vec3(0.6f);
  s.colors.assign(s.vertexCount(), glm::vec3(1.0f));  // the cup's own are not white
  const ShearingCamera cam(*s.camera, 80, 60, 3);
  for (const char* spec : {"svr", "mvr:cpu", "mvr:exact"}) {
    const test::CaptureSink views = test::renderSpec(spec, s, cam);
    int covered = 0;
    for (const auto& [key, img] : views.views)
      for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) {
          const glm::vec4 p = img.linear(x, y);
          if (p.a < 1.0f) continue;
          ++covered;
          EXPECT_NEAR(p.g, 0.6f, 0.006f) << spec << " at " << x << "," << y;
        }
    EXPECT_GT(covered, 500) << spec;
  }
}

TEST_F(ImageLightRender, AMirrorShowsTheMap) {
  // A mirror (metal, base 1, roughness 0) square on the image plane under
  // L(d) = 0.5 + 0.4 d: the centre view's centre pixel sees the map
  // straight back, towards +z, times the lobe's directional albedo at
  // normal incidence (A + B, about 1); the left view's mirror direction
  // leans to +x (redder), the right view's to -x.
  Scene s = loadScene(test::assetPath("plane.obj"));
  s.materials.assign(1, Material{});
  s.materials[0].setMetallicRoughness(glm::vec3(1.0f), 1.0f, 0.0f);
  s.materialIds.assign(s.triangleCount(), 0);
  s.colors.assign(s.vertexCount(), glm::vec3(1.0f));
  s.lights.clear();
  s.ambient = glm::vec3(0.0f);
  s.environment = Environment{"map"};
  s.environment->light = std::make_shared<const ImageLight>(equirect(256, [](glm::vec3 d) { return glm::vec3(0.5f) + 0.4f * d; }));
  CameraSpec spec;
  spec.distance = 3.0, spec.planeWidth = 1.2, spec.trackLeft = -1.0, spec.trackRight = 1.0;
  spec.nearDistance = 1.0, spec.farDistance = 5.0;
  const ShearingCamera cam(spec, 64, 48, 3);
  const glm::vec2 e = shading::dfg(0.0f, 1.0f);
  for (const char* backend : {"svr", "mvr:cpu", "mvr:exact"}) {
    const test::CaptureSink views = test::renderSpec(backend, s, cam);
    const glm::vec4 centre = views.views.at({0, 1}).linear(32, 24);
    EXPECT_NEAR(centre.r, 0.5f * (e.x + e.y), 0.02f) << backend;
    EXPECT_NEAR(centre.b, 0.9f * (e.x + e.y), 0.02f) << backend;
    const float left = views.views.at({0, 0}).linear(32, 24).r, right = views.views.at({0, 2}).linear(32, 24).r;
    EXPECT_GT(left, centre.r + 0.05f) << backend;
    EXPECT_LT(right, centre.r - 0.05f) << backend;
  }
}

TEST_F(ImageLightRender, EveryModeMatchesSvrUnderAnEnvironment) {
  const glm::vec3 sun = glm::normalize(glm::vec3(0.4f, 0.6f, 0.7f));
  const Scene s = furnaceScene(equirect(256, [&](glm::vec3 d) {
    return glm::vec3(0.3f, 0.4f, 0.6f) * (0.5f + 0.5f * d.y) + glm::vec3(3.0f) * std::pow(std::max(glm::dot(d, sun), 0.0f), 32.0f);
  }));
  test::expectHighlightsMatchSvr(s, ShearingCamera(*s.camera, 120, 90, 6));
}

}  // namespace
}  // namespace mvr
