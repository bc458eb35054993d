// Spot lights (glTF's KHR_lights_punctual cone): the falloff by hand, and a
// sphere lit by one spot, whose cap inside the cone is lit and whose rim
// outside it has the ambient light only, in every back end against SVR.
// Tolerances as for any diffuse scene (lighting.h: one formula per vertex
// for MVR and SVR, per pixel for deferred).
#include <gtest/gtest.h>

#include <cmath>

#include "shading/lighting.h"
#include "tests/support/meshes.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

Light spotDown(float innerDegrees, float outerDegrees) {
  Light spot;
  spot.type = Light::Type::Spot;
  spot.vector = glm::vec3(0, 0, 3);
  spot.axis = glm::vec3(0, 0, -1);
  spot.cosInner = std::cos(glm::radians(innerDegrees));
  spot.cosOuter = std::cos(glm::radians(outerDegrees));
  return spot;
}

// l: from a point on z = 0 at angle a off the spot's axis towards the spot.
glm::vec3 towardsSpotAt(float degrees) {
  const float a = glm::radians(degrees);
  return glm::vec3(-std::sin(a), 0.0f, std::cos(a));
}

TEST(SpotLight, FallsOffAsGltfSays) {
  const Light spot = spotDown(10.0f, 20.0f);
  EXPECT_FLOAT_EQ(coneFactor(spot, towardsSpotAt(0.0f)), 1.0f);
  EXPECT_FLOAT_EQ(coneFactor(spot, towardsSpotAt(10.0f)), 1.0f);
  EXPECT_FLOAT_EQ(coneFactor(spot, towardsSpotAt(25.0f)), 0.0f);
  // Half way in cosine between the cones: t = 1/2, a quarter of the light.
  const float half = std::acos(0.5f * (spot.cosInner + spot.cosOuter));
  EXPECT_NEAR(coneFactor(spot, towardsSpotAt(glm::degrees(half))), 0.25f, 1e-4f);
  // Behind the spot: none. Any other light: all of it, in any direction.
  EXPECT_EQ(coneFactor(spot, glm::vec3(0, 0, -1)), 0.0f);
  Light point = spot;
  point.type = Light::Type::Point;
  EXPECT_EQ(coneFactor(point, glm::vec3(0, 0, -1)), 1.0f);
  // A cone with no falloff band is a hard edge, not a division by zero.
  const Light hard = spotDown(15.0f, 15.0f);
  EXPECT_EQ(coneFactor(hard, towardsSpotAt(14.0f)), 1.0f);
  EXPECT_EQ(coneFactor(hard, towardsSpotAt(16.0f)), 0.0f);
}

TEST(SpotLight, DiffuseTakesTheCone) {
  Scene s;
  s.ambient = glm::vec3(0.0f);
  s.lights = {spotDown(10.0f, 20.0f)};
  const glm::vec3 up(0, 0, 1);
  // Straight below the spot: full light; 3 tan 30 off the axis: none.
  EXPECT_NEAR(shading::diffuse(s, glm::vec3(1), glm::vec3(0), up).x, 1.0f, 1e-6f);
  const glm::vec3 outside(3.0f * std::tan(glm::radians(30.0f)), 0, 0);
  EXPECT_EQ(shading::diffuse(s, glm::vec3(1), outside, up), glm::vec3(0));
  s.lights[0].type = Light::Type::Point;
  EXPECT_GT(shading::diffuse(s, glm::vec3(1), outside, up).x, 0.5f);
}

// The unit sphere under a 5-12 degree spot 3 above it: the cap it lights
// reaches about 0.43 off the centre; at 0.8 only the ambient light is left.
class SpotLightVsSvr : public test::GlTest {
 protected:
  static Scene litSphere() {
    Scene s = test::sphereScene(1.0f, 48, 96);
    s.ambient = glm::vec3(0.05f);
    s.lights = {spotDown(5.0f, 12.0f)};
    return s;
  }
  static ShearingCamera camera(int views) {
    CameraSpec spec;
    spec.planeWidth = 2.4;
    return ShearingCamera(spec, 96, 96, views);
  }
};

TEST_F(SpotLightVsSvr, LightsItsConeAlone) {
  const Scene scene = litSphere();
  auto svr = makeSvrRenderer(scene, PixelType::U8);
  const test::CaptureSink views = test::renderViews(*svr, camera(3));
  const Image& centre = views.views.at({0, 1});
  const float lit = centre.linear(48, 48).r, rim = centre.linear(48 + 32, 48).r;
  EXPECT_GT(lit, 0.5f);        // 0.6 albedo x (0.05 ambient + about 1)
  EXPECT_LT(rim, 0.05f);       // 0.6 x 0.05 ambient
  EXPECT_GT(rim, 0.01f);       // but the sphere is there
}

TEST_F(SpotLightVsSvr, EveryModeMatchesSvr) {
  const test::BackEndsAgainstSvr r = test::compareBackEndsWithSvr(litSphere(), camera(6));
  EXPECT_EQ(r.difference.at("svr-layered").minIdentical, 1.0);
  // Deferred lights per pixel, the others per vertex: the cone's edge
  // differs by up to a few levels across a triangle.
  EXPECT_GE(r.difference.at("deferred").minPsnr, 35.0);
  for (const char* mode : {"cpu", "exact", "strip", "quad"}) EXPECT_GE(r.difference.at(mode).minPsnr, 40.0) << mode;
}

}  // namespace
}  // namespace mvr
