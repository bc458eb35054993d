// MVR against SVR on the same scene and camera, per view. Tolerances:
//  cpu, exact  >= 99.5% identical pixels and PSNR >= 40 dB; what differs is
//              silhouette pixels where the two rasterizers' fill rules and
//              sub-pixel snapping disagree, and 1-LSB rounding of colours.
//              (At 96 x 72 one full-contrast silhouette pixel alone costs
//              42 dB, so 45 dB would demand pixel-identical silhouettes.)
//  strip       PSNR >= 40 dB: slivers interpolate linearly between exact
//              rulings, half a pixel of attribute misplacement at most.
//  quad        on a strongly twisted scene, measurably worse than strip.
#include <gtest/gtest.h>

#include <cstring>

#include "mvr/io/scene_io.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

class MvrVsSvr : public test::GlTest {
 protected:
  test::SetDifference run(const Scene& scene, const ShearingCamera& cam, PstMode mode) {
    auto svr = makeSvrRenderer(scene, PixelType::U8);
    auto mvr = makeMvrRenderer(scene, mode, PixelType::U8);
    return test::compareViews(test::renderViews(*svr, cam), test::renderViews(*mvr, cam));
  }
};

TEST_F(MvrVsSvr, CubeExactModesMatch) {
  Scene scene = loadScene(test::assetPath("cube.json"));
  ShearingCamera cam(*scene.camera, 96, 72, 9);
  for (PstMode mode : {PstMode::Cpu, PstMode::Exact}) {
    auto d = run(scene, cam, mode);
    EXPECT_GE(d.minIdentical, 0.995) << pstModeName(mode);
    EXPECT_GE(d.minPsnr, 40.0) << pstModeName(mode);
  }
}

TEST_F(MvrVsSvr, TeacupExactModesMatchAndStripIsClose) {
  Scene scene = loadScene(test::assetPath("default.json"));
  ShearingCamera cam(*scene.camera, 120, 90, 7);
  for (PstMode mode : {PstMode::Cpu, PstMode::Exact}) {
    auto d = run(scene, cam, mode);
    EXPECT_GE(d.minIdentical, 0.995) << pstModeName(mode);
    EXPECT_GE(d.minPsnr, 40.0) << pstModeName(mode);
  }
  auto strip = run(scene, cam, PstMode::Strip);
  EXPECT_GE(strip.minPsnr, 40.0);
}

// A quad running steeply in depth, coloured red (near) to green (far): its
// slices twist strongly across a wide track.
Scene twistedScene() {
  Scene s;
  s.positions = {{-1.2f, -0.8f, 1.8f}, {1.2f, -0.8f, -3.0f}, {1.2f, 0.8f, -3.0f}, {-1.2f, 0.8f, 1.8f}};
  s.normals.assign(4, glm::vec3(0, 0, 1));
  s.colors = {{1, 0, 0}, {0, 1, 0.2f}, {0, 0.2f, 1}, {1, 1, 0}};
  s.triangles = {{0, 1, 2}, {0, 2, 3}};
  s.materialIds = {0, 0};
  Material m;
  m.diffuse = glm::vec3(1);
  s.materials = {m};
  s.ambient = glm::vec3(1);  // unlit: colours exactly as given
  return s;
}

TEST_F(MvrVsSvr, QuadIsMeasurablyWorseOnATwistedScene) {
  Scene scene = twistedScene();
  CameraSpec spec;
  spec.distance = 4;
  spec.planeWidth = 3;
  spec.trackLeft = -3;
  spec.trackRight = 3;
  spec.nearDistance = 1;
  spec.farDistance = 9;
  ShearingCamera cam(spec, 96, 64, 16);
  auto quad = run(scene, cam, PstMode::Quad);
  auto strip = run(scene, cam, PstMode::Strip);
  auto exact = run(scene, cam, PstMode::Exact);
  EXPECT_GE(exact.minPsnr, 40.0);
  EXPECT_GE(strip.minPsnr, 35.0);
  EXPECT_LT(quad.minPsnr, strip.minPsnr - 3.0) << "quad " << quad.minPsnr << " strip " << strip.minPsnr;
}

TEST_F(MvrVsSvr, OneAndTwoViews) {
  Scene scene = loadScene(test::assetPath("cube.json"));
  for (int n : {1, 2}) {
    ShearingCamera cam(*scene.camera, 64, 48, n);
    auto d = run(scene, cam, PstMode::Cpu);
    EXPECT_GE(d.minIdentical, 0.995) << n << " views";
  }
}

TEST_F(MvrVsSvr, EpiOrderReorderedEqualsViews) {
  Scene scene = loadScene(test::assetPath("cube.json"));
  ShearingCamera cam(*scene.camera, 40, 30, 5);
  auto mvr = makeMvrRenderer(scene, PstMode::Exact, PixelType::U8);
  test::CaptureSink epis;
  RenderStats stats;
  mvr->render(cam, epis, stats);
  ASSERT_EQ(epis.epis.size(), 30u);
  test::CaptureSink views = test::renderViews(*mvr, cam);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 30; ++j)
      ASSERT_EQ(0, std::memcmp(views.views.at({0, i}).row(j), epis.epis.at({0, j}).row(i), 40 * 4))
          << "view " << i << " scanline " << j;
  EXPECT_GT(stats.counters["slices"], 0);
  EXPECT_TRUE(stats.times.seconds.count("slicing"));
}

}  // namespace
}  // namespace mvr
