// glTF's metallic-roughness BRDF (shading/brdf.h) against values derived
// by hand, its lobe's normalisation by numerical integration, and the
// C++ specularLight of a Ggx material against the lobe.
#include <cmath>

#include <gtest/gtest.h>

#include "shading/brdf.h"
#include "shading/view_dependent.h"

namespace mvr {
namespace {

const glm::vec3 kZ(0.0f, 0.0f, 1.0f);

TEST(Brdf, NormalIncidenceReflectsF0OverFourAlphaSquared) {
  // n = l = v: h = n, v.h = 1 so F = F0; D = 1 / (pi alpha^2); the Smith
  // terms are both 1, so V = 0.5 / 2 = 1/4. pi F V D = F0 / (4 alpha^2).
  const glm::vec3 f0(0.04f, 0.5f, 1.0f);
  for (float roughness : {0.3f, 0.5f, 1.0f}) {
    const float alpha = roughness * roughness;
    const glm::vec3 c = shading::ggxLobe(f0, 1.0f, roughness, kZ, kZ, kZ);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], f0[k] / (4.0f * alpha * alpha), 1e-4f * c[k]) << roughness;
  }
}

TEST(Brdf, FresnelRunsFromF0ToF90AtGrazing) {
  const glm::vec3 f0(0.04f, 0.2f, 0.9f);
  EXPECT_EQ(shading::schlickFresnel(f0, 1.0f, 1.0f), f0);
  EXPECT_EQ(shading::schlickFresnel(f0, 1.0f, 0.0f), glm::vec3(1.0f));
  EXPECT_EQ(shading::schlickFresnel(f0, 0.5f, 0.0f), glm::vec3(0.5f));  // KHR_materials_specular's F90
  // Halfway in angle: (1 - cos 60)^5 = 1/32 of the way.
  EXPECT_NEAR(shading::schlickFresnel(f0, 1.0f, 0.5f).r, 0.04f + 0.96f / 32.0f, 1e-6f);
}

TEST(Brdf, NothingBelowTheHorizon) {
  const glm::vec3 below = glm::normalize(glm::vec3(1.0f, 0.0f, -0.1f));
  EXPECT_EQ(shading::ggxLobe(glm::vec3(1.0f), 1.0f, 0.5f, kZ, below, kZ), glm::vec3(0.0f));
  EXPECT_EQ(shading::ggxLobe(glm::vec3(1.0f), 1.0f, 0.5f, kZ, kZ, below), glm::vec3(0.0f));
}

// The distribution's projected area is one at every roughness: the
// integral of D(h) (n.h) over the hemisphere, in (cos theta, phi).
double projectedArea(float alpha) {
  const int steps = 200000;
  double sum = 0.0;
  for (int i = 0; i < steps; ++i) {
    const double c = (i + 0.5) / steps;  // cos theta; d omega = d cos theta d phi
    sum += shading::ggxDistribution(alpha, float(c)) * c;
  }
  return sum * 2.0 * M_PI / steps;
}

TEST(Brdf, DistributionIsNormalisedAtEveryRoughness) {
  for (float roughness : {1.0f, 0.5f, 0.2f, 0.1f})
    EXPECT_NEAR(projectedArea(roughness * roughness), 1.0, 2e-3) << roughness;
}

TEST(Brdf, RoughnessTowardsZeroStaysFinite) {
  // Below kMinRoughness the lobe is that of kMinRoughness: a peak of
  // F0 / (4 alpha^2) at the mirror direction, finite, no NaN.
  const float a = shading::kMinRoughness * shading::kMinRoughness;
  for (float roughness : {0.0f, 1e-6f, shading::kMinRoughness}) {
    const glm::vec3 c = shading::ggxLobe(glm::vec3(0.5f), 1.0f, roughness, kZ, kZ, kZ);
    EXPECT_TRUE(std::isfinite(c.r));
    EXPECT_NEAR(c.r, 0.5f / (4.0f * a * a), 1e-3f * c.r);
  }
  // Off the mirror by 2 theta = 10 degrees: D in its other form,
  // alpha^2 / (pi cos^4 theta (alpha^2 + tan^2 theta)^2), the tail GGX keeps.
  const double theta = 5.0 * M_PI / 180.0, t2 = std::pow(std::tan(theta), 2.0);
  const double d = a * a / (M_PI * std::pow(std::cos(theta), 4.0) * std::pow(a * a + t2, 2.0));
  EXPECT_NEAR(shading::ggxDistribution(a, float(std::cos(theta))), d, 1e-4 * d);
  const glm::vec3 l = glm::normalize(glm::vec3(std::sin(2 * theta), 0.0f, std::cos(2 * theta)));
  EXPECT_LT(shading::ggxLobe(glm::vec3(0.5f), 1.0f, 0.0f, kZ, l, kZ).r, 1e-5f * 0.5f / (4.0f * a * a));
}

TEST(Brdf, ASpecularLightOfAGgxMaterialIsTheLobeTimesTheLight) {
  Scene s;
  Material m;
  m.setMetallicRoughness(glm::vec3(0.9f, 0.6f, 0.3f), 1.0f, 0.4f);
  EXPECT_EQ(m.diffuse, glm::vec3(0.0f));  // a metal: no diffuse part
  EXPECT_EQ(m.specular, glm::vec3(0.9f, 0.6f, 0.3f));  // F0 = base
  s.materials = {m};
  const glm::vec3 l = glm::normalize(glm::vec3(1, 0, 1));
  s.lights = {Light{Light::Type::Directional, -l, glm::vec3(0.5f)}};
  const glm::vec3 eye(-3.0f, 0.5f, 4.0f), v = glm::normalize(eye);
  // The lobe, lifted by what single scattering loses (three.js's direct light).
  const glm::vec3 expect = 0.5f * shading::ggxLobe(m.specular, 1.0f, 0.4f, kZ, l, v) *
                           shading::multiScatterCompensation(m.specular, 0.4f, v.z);
  const glm::vec3 c = shading::specularLight(s, m, glm::vec3(0), 2.0f * kZ, eye);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(c[k], expect[k], 1e-5f);
  EXPECT_GT(c.r, 0.0f);
}

TEST(Brdf, DielectricKeepsItsBaseAsDiffuseAndAFourPercentF0) {
  Material m;
  m.setMetallicRoughness(glm::vec3(0.5f, 0.25f, 1.0f), 0.0f, 0.5f);
  EXPECT_EQ(m.specularModel, SpecularModel::Ggx);
  EXPECT_EQ(m.diffuse, glm::vec3(0.5f, 0.25f, 1.0f));
  EXPECT_EQ(m.specular, glm::vec3(0.04f));
  EXPECT_EQ(m.roughness, 0.5f);
  // Half metal: half the base diffuse, F0 halfway between 0.04 and base.
  m.setMetallicRoughness(glm::vec3(0.5f, 0.25f, 1.0f), 0.5f, 0.5f, glm::vec3(0.1f), 0.6f);
  EXPECT_NEAR(glm::distance(m.diffuse, glm::vec3(0.25f, 0.125f, 0.5f)), 0.0f, 1e-6f);
  EXPECT_NEAR(glm::distance(m.specular, glm::vec3(0.3f, 0.175f, 0.55f)), 0.0f, 1e-6f);
  EXPECT_NEAR(m.specularF90, 0.8f, 1e-6f);
}

}  // namespace
}  // namespace mvr

namespace mvr {
namespace {

TEST(Brdf, SplitSumTableMatchesThreeJsAndItsLimits) {
  const std::vector<glm::vec2>& t = shading::dfgTable();
  ASSERT_EQ(t.size(), size_t(shading::kDfgSize * shading::kDfgSize));
  auto cell = [&](int i, int j) { return t[size_t(j * shading::kDfgSize + i)]; };
  // three.js r187's own table (src/renderers/shaders/DFGLUTData.js, half
  // floats, 4096 samples a cell) at cells (roughness i, n.v j): the same
  // integral, so the same values to within sampling and rounding.
  const struct { int i, j; float a, b; } three[] = {{0, 0, 0.1471f, 0.8521f}, {5, 5, 0.8379f, 0.0938f},
                                                    {15, 15, 0.3452f, 0.0001f}, {15, 0, 0.8599f, 0.0390f},
                                                    {0, 15, 1.0000f, 0.0000f}, {8, 2, 0.7593f, 0.1009f}};
  for (const auto& c : three) {
    EXPECT_NEAR(cell(c.i, c.j).x, c.a, 0.01f) << c.i << ", " << c.j;
    EXPECT_NEAR(cell(c.i, c.j).y, c.b, 0.01f) << c.i << ", " << c.j;
  }
  // A near-mirror reflects all it is lit by (A + B = 1); head-on, Schlick's
  // term is nothing (B = 0).
  for (int j = 2; j < shading::kDfgSize; ++j) EXPECT_NEAR(cell(0, j).x + cell(0, j).y, 1.0f, 0.02f) << j;
  EXPECT_NEAR(shading::dfg(0.0f, 1.0f).y, 0.0f, 1e-3f);
  // Rough surfaces lose energy to single scattering, which the
  // compensation gives back: white F0 at roughness 1 is lifted by 1 / E.
  const glm::vec2 e = shading::dfg(1.0f, 0.5f);
  EXPECT_LT(e.x + e.y, 0.8f);
  EXPECT_NEAR(shading::multiScatterCompensation(glm::vec3(1.0f), 1.0f, 0.5f).x, 1.0f / (e.x + e.y), 1e-5f);
  EXPECT_EQ(shading::multiScatterCompensation(glm::vec3(0.0f), 1.0f, 0.5f), glm::vec3(1.0f));
}

}  // namespace
}  // namespace mvr
