// A renderer following its scene as it moves (Renderer::sceneMoved,
// mvr/scene_pose.h): after the scene is posed in place, what a back end
// that follows renders is what a new renderer of the posed scene renders,
// to the byte; one that cannot says so. And the turntable by hand: a
// quarter turn takes +x to -z about the pivot, and a whole turn is the
// identity.
#include <gtest/gtest.h>

#include "mvr/backends/backend.h"
#include "mvr/assets/scene_io.h"
#include "mvr/scene_pose.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

TEST(Turntable, AQuarterTurnTakesXToMinusZAboutThePivot) {
  const glm::vec3 pivot(1.0f, 2.0f, 3.0f);
  const glm::mat4 m = turntable(pivot, 90.0);
  const glm::vec3 p = glm::vec3(m * glm::vec4(pivot + glm::vec3(1, 5, 0), 1.0f));
  EXPECT_NEAR(glm::distance(p, pivot + glm::vec3(0, 5, -1)), 0.0f, 1e-6f);
  EXPECT_EQ(turntable(pivot, 360.0), glm::mat4(1.0f));
  EXPECT_EQ(turntable(pivot, 0.0), glm::mat4(1.0f));
}

TEST(Turntable, PosesGeometryAndLeavesLightsInTheWorld) {
  Scene still = loadScene(test::assetPath("default.json"));
  Scene posed = still;
  const std::vector<Light> lights = still.lights;
  poseGeometry(posed, still, turntable(still.bounds().center(), 180.0));
  EXPECT_NE(posed.positions, still.positions);
  EXPECT_EQ(posed.lights.size(), lights.size());
  for (size_t i = 0; i < lights.size(); ++i) EXPECT_EQ(posed.lights[i].vector, lights[i].vector);
  poseGeometry(posed, still, glm::mat4(1.0f));  // from the still, not from the last pose
  EXPECT_EQ(posed.positions, still.positions);
  EXPECT_EQ(posed.normals, still.normals);
}

// Frame 0 rendered, the scene turned, then the follower against a new
// renderer of the posed scene.
void expectFollowingEqualsANewRenderer(const std::string& spec, const std::string& asset) {
  test::sharedContext();
  const Scene still = loadScene(test::assetPath(asset));
  Scene scene = still;
  const ShearingCamera cam(cameraFor(still, 64, 48), 64, 48, 5);
  const BackendOptions backend = parseBackendSpec(spec);
  auto follower = makeRenderer(backend, scene, PixelType::U8);
  (void)test::renderViews(*follower, cam);  // frame 0, so that whatever it derived is stale
  poseGeometry(scene, still, turntable(still.bounds().center(), 70.0));
  const bool follows = follower->sceneMoved();
  if (backend.backend == Backend::Interp || backend.backend == Backend::Warp) {
    EXPECT_FALSE(follows) << "its source views are of the old pose";
    return;
  }
  ASSERT_TRUE(follows);
  auto fresh = makeRenderer(backend, scene, PixelType::U8);
  const test::SetDifference d = test::compareViews(test::renderViews(*fresh, cam), test::renderViews(*follower, cam));
  EXPECT_EQ(d.minIdentical, 1.0) << spec;
}

class SceneMovedTest : public ::testing::TestWithParam<const char*> {};

TEST_P(SceneMovedTest, FollowingEqualsANewRenderer) { expectFollowingEqualsANewRenderer(GetParam(), "textured.json"); }

// The GPU spans take a diffuse scene; their GPU transform's buffers are
// written again, not made anew.
TEST(SceneMoved, GpuSpansFollowingEqualsANewRenderer) {
  expectFollowingEqualsANewRenderer("mvr:spans", "default.json");
}

INSTANTIATE_TEST_SUITE_P(EveryBackend, SceneMovedTest,
                         ::testing::Values("mvr:cpu", "mvr:exact", "mvr:strip:gpu-psts", "svr", "svr-layered",
                                           "deferred", "interp:dual", "warp:dual:cpu"),
                         test::specTestName);

}  // namespace
}  // namespace mvr
