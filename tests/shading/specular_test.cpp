// View-dependent shading: the formula checked by hand, and every MVR mode
// against SVR on a scene with Phong and Blinn-Phong materials. Tolerances:
//  cpu, exact   >= 99.5% identical pixels, PSNR >= 40 dB (as for diffuse)
//  strip, quad  PSNR >= 40 dB: the highlight is interpolated linearly
//               across slivers, so single 8-bit steps are common.
//  svr-layered  identical to svr.
#include <gtest/gtest.h>

#include "mvr/assets/scene_io.h"
#include "shading/shading_plan.h"
#include "shading/view_dependent.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

Scene oneLight(SpecularModel model, float shininess) {
  Scene s;
  Material m;
  m.specular = glm::vec3(0.5f, 0.25f, 1.0f);
  m.shininess = shininess;
  m.specularModel = model;
  s.materials = {m};
  s.lights = {Light{Light::Type::Directional, glm::normalize(glm::vec3(-1, 0, -1)), glm::vec3(1)}};
  return s;
}

TEST(Specular, MirrorDirectionGivesTheFullHighlight) {
  // Towards the light l = (1, 0, 1)/sqrt2; its mirror image about n = z is
  // (-1, 0, 1)/sqrt2, and an eye along it sees the full specular colour.
  for (SpecularModel model : {SpecularModel::Phong, SpecularModel::BlinnPhong}) {
    Scene s = oneLight(model, 20.0f);
    const glm::vec3 c = shading::specularLight(s, s.materials[0], glm::vec3(0), glm::vec3(0, 0, 2),
                                               glm::vec3(-3, 0, 3));
    EXPECT_NEAR(c.r, 0.5f, 1e-5f);
    EXPECT_NEAR(c.g, 0.25f, 1e-5f);
    EXPECT_NEAR(c.b, 1.0f, 1e-5f);
  }
}

TEST(Specular, PhongAndBlinnPhongDifferOffTheMirrorDirection) {
  // Eye straight above: Phong's angle is 45 degrees between r and v,
  // Blinn-Phong's is 22.5 degrees between n and h.
  const glm::vec3 eye(0, 0, 5);
  Scene phong = oneLight(SpecularModel::Phong, 4.0f), blinn = oneLight(SpecularModel::BlinnPhong, 4.0f);
  const float p = shading::specularLight(phong, phong.materials[0], glm::vec3(0), glm::vec3(0, 0, 1), eye).b;
  const float b = shading::specularLight(blinn, blinn.materials[0], glm::vec3(0), glm::vec3(0, 0, 1), eye).b;
  EXPECT_NEAR(p, std::pow(std::cos(glm::radians(45.0f)), 4.0f), 1e-5f);
  EXPECT_NEAR(b, std::pow(std::cos(glm::radians(22.5f)), 4.0f), 1e-5f);
}

TEST(Specular, NoHighlightFromBehindOrWithoutSpecularColour) {
  Scene s = oneLight(SpecularModel::Phong, 8.0f);
  EXPECT_EQ(shading::specularLight(s, s.materials[0], glm::vec3(0), glm::vec3(0, 0, -1), glm::vec3(-3, 0, 3)),
            glm::vec3(0));
  EXPECT_EQ(shading::specularLight(s, s.materials[0], glm::vec3(0), glm::vec3(0), glm::vec3(-3, 0, 3)),
            glm::vec3(0));  // degenerate normal: no NaN
  s.materials[0].specular = glm::vec3(0);
  EXPECT_EQ(shading::specularLight(s, s.materials[0], glm::vec3(0), glm::vec3(0, 0, 1), glm::vec3(-3, 0, 3)),
            glm::vec3(0));
}

TEST(PassPlan, ScenesPayOnlyForTheirMaterials) {
  Scene diffuse = loadScene(test::assetPath("default.json"));
  EXPECT_EQ(shading::planShading(diffuse).passNames(), "diffuse");
  EXPECT_EQ(shading::planShading(diffuse).extraCount, 0);
  Scene shiny = loadScene(test::assetPath("shiny.json"));
  const shading::ShadingPlan plan = shading::planShading(shiny);
  EXPECT_EQ(plan.passNames(), "diffuse+view-dependent");
  EXPECT_EQ(plan.extraCount, 6);  // position and normal
  shiny.materials[0].reflectionMap = "env.png";
  EXPECT_EQ(shading::planShading(shiny).extraCount, 15);
}

class SpecularVsSvr : public test::GlTest {};

TEST_F(SpecularVsSvr, EveryModeMatchesSvr) {
  const Scene scene = loadScene(test::assetPath("shiny.json"));
  test::expectHighlightsMatchSvr(scene, ShearingCamera(*scene.camera, 120, 90, 6));
}

TEST_F(SpecularVsSvr, HighlightsMoveWithTheViewAndTheRow) {
  Scene scene = loadScene(test::assetPath("shiny.json"));
  scene.camera->rowTop = 0.8;
  scene.camera->rowBottom = -0.8;
  ShearingCamera cam(*scene.camera, 80, 60, 3, 2);
  auto svr = makeSvrRenderer(scene, PixelType::U8);
  auto cpu = makeMvrRenderer(scene, PstMode::Cpu, PixelType::U8);
  const test::CaptureSink a = test::renderViews(*svr, cam), b = test::renderViews(*cpu, cam);
  test::expectCloseOnAnyGl(test::compareViews(a, b), 0.995, 40.0, "cpu");
  // Without the highlight, the same views differ from these.
  Scene matte = scene;
  for (Material& m : matte.materials) m.specular = glm::vec3(0);
  auto flat = makeMvrRenderer(matte, PstMode::Cpu, PixelType::U8);
  const test::CaptureSink c = test::renderViews(*flat, cam);
  EXPECT_LT(compareImages(b.views.at({1, 2}), c.views.at({1, 2})).identicalFraction, 0.97);
}

}  // namespace
}  // namespace mvr

namespace mvr {
namespace {

// Enough views that the EPIs of one row need several batches: the later
// passes test depth EQUAL with depth writes off, and the next batch's clear
// must still reset depth.
TEST_F(SpecularVsSvr, PassesSurviveSeveralBatches) {
  Scene scene = loadScene(test::assetPath("textured.json"));
  ShearingCamera cam(*scene.camera, 40, 48, 1000);
  auto exact = makeMvrRenderer(scene, PstMode::Exact, PixelType::U8, TextureMode::Direct);
  auto cpu = makeMvrRenderer(scene, PstMode::Cpu, PixelType::U8);
  RenderStats stats;
  const test::CaptureSink a = test::renderViews(*exact, cam, stats);
  ASSERT_LT(stats.counters["epis_per_draw"], cam.height());
  const test::CaptureSink b = test::renderViews(*cpu, cam);
  // Texture filtering arithmetic differs (about 34 dB at this size); a stale
  // depth buffer drops whole polygons (about 14 dB).
  EXPECT_GE(test::compareViews(a, b).minPsnr, 30.0);
}

}  // namespace
}  // namespace mvr
