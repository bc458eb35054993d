// glTF's metallic-roughness in every back end: the bundled metal_rough
// scene (a rough gold cup, a red dielectric cube) through every MVR mode
// against SVR. Tolerances as for the Blinn-Phong highlights
// (specular_test.cpp): PSNR >= 40 dB everywhere, and the CPU spans and
// the exact mode near-identical. The GGX pass also takes the Fresnel
// share off the diffuse light, so these compare that too.
#include <gtest/gtest.h>

#include "mvr/assets/scene_io.h"
#include "shading/shading_plan.h"
#include "shading/view_dependent.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

TEST(PbrPlan, AMetallicRoughnessSceneCarriesItsAlbedo) {
  const Scene scene = loadScene(test::assetPath("metal_rough.json"));
  ASSERT_EQ(scene.materials.size(), 2u);
  EXPECT_EQ(scene.materials[0].specularModel, SpecularModel::Ggx);
  EXPECT_EQ(scene.materials[0].diffuse, glm::vec3(0.0f));  // metal
  const shading::ShadingPlan plan = shading::planShading(scene);
  EXPECT_EQ(plan.passNames(), "diffuse+view-dependent");
  EXPECT_TRUE(plan.ggx);
  EXPECT_EQ(plan.albedo, plan.normal + 3);  // one run with position and normal
  EXPECT_EQ(plan.extraCount, 9);
}

TEST(PbrPlan, FresnelTakesItsShareOffTheDiffuse) {
  // A white dielectric lit head-on and seen at grazing: F(v.h) grows as the
  // eye leaves the light's direction, and so does what the diffuse loses.
  Scene s;
  Material m;
  m.setMetallicRoughness(glm::vec3(1.0f), 0.0f, 0.5f);
  s.materials = {m};
  s.ambient = glm::vec3(0.0f);
  s.lights = {Light{Light::Type::Directional, glm::vec3(0, 0, -1), glm::vec3(1.0f)}};
  const glm::vec3 n(0, 0, 1), p(0.0f);
  const float headOn = shading::diffuseFresnelLoss(s, m, glm::vec3(1.0f), p, n, glm::vec3(0, 0, 5)).r;
  EXPECT_NEAR(headOn, 0.04f, 1e-6f);  // v.h = 1: F = F0
  const glm::vec3 grazing(5.0f, 0.0f, 0.3f);
  const float h = glm::dot(glm::normalize(grazing), glm::normalize(glm::normalize(grazing) + n));
  EXPECT_NEAR(shading::diffuseFresnelLoss(s, m, glm::vec3(1.0f), p, n, grazing).r,
              0.04f + 0.96f * std::pow(1.0f - h, 5.0f), 1e-5f);
  // A metal has no diffuse part to lose; other models lose nothing.
  Material metal;
  metal.setMetallicRoughness(glm::vec3(1.0f), 1.0f, 0.5f);
  EXPECT_EQ(shading::diffuseFresnelLoss(s, metal, metal.diffuse, p, n, grazing), glm::vec3(0.0f));
  Material phong;
  phong.specular = glm::vec3(1.0f);
  EXPECT_EQ(shading::diffuseFresnelLoss(s, phong, glm::vec3(1.0f), p, n, grazing), glm::vec3(0.0f));
}

class PbrVsSvr : public test::GlTest {};

TEST_F(PbrVsSvr, EveryModeMatchesSvr) {
  const Scene scene = loadScene(test::assetPath("metal_rough.json"));
  test::expectHighlightsMatchSvr(scene, ShearingCamera(*scene.camera, 120, 90, 6));
}

}  // namespace
}  // namespace mvr
