// Anti-aliasing every back end shares (mvr/frames/supersampling.h), checked by
// hand: a quad on the image plane (zero disparity, so every view and every
// perspective sample sees it alike) whose edges cut pixels at known
// fractions, and MVR against SVR with both supersampled.
#include <gtest/gtest.h>

#include "mvr/backends/backend.h"
#include "mvr/frames/supersampling.h"
#include "mvr/assets/scene_io.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

// Renders cam's views with aa through the shared filter.
test::CaptureSink renderFiltered(Renderer& renderer, const ShearingCamera& cam, const Supersampling& aa) {
  test::CaptureSink capture;
  EpisToViews reorder(capture, cam.width(), cam.height(), cam.views(), PixelType::U8);
  FrameSink& views = renderer.order() == FrameOrder::Epi ? static_cast<FrameSink&>(reorder) : capture;
  SupersampleSink filter(views, aa, cam.width(), cam.height(), cam.views());
  RenderStats stats;
  renderer.render(supersampledCamera(cam, aa), filter, stats);
  filter.finish();
  return capture;
}

// Unlit, one colour: x and y from -0.4375 to 0.4375 on the image plane.
// With a 2 x 2 plane on 8 x 8 pixels, pixel u = 4 (x + 1): the edges lie
// at u = 2.25 and 5.75, so columns 2 and 5 (and rows) are 3/4 covered.
Scene edgeQuad() {
  Scene s;
  const float e = 0.4375f;
  s.positions = {{-e, -e, 0}, {e, -e, 0}, {e, e, 0}, {-e, e, 0}};
  s.normals.assign(4, glm::vec3(0, 0, 1));
  s.colors.assign(4, glm::vec3(0.8f, 0.4f, 0.2f));
  s.triangles = {{0, 1, 2}, {0, 2, 3}};
  s.materialIds = {0, 0};
  Material m;
  m.diffuse = glm::vec3(1);
  s.materials = {m};
  s.ambient = glm::vec3(1);
  return s;
}

class Antialiasing : public test::GlTest {};

TEST_F(Antialiasing, EdgePixelsCoverTheirFractionInEveryBackEnd) {
  const Scene scene = edgeQuad();
  const ShearingCamera cam(CameraSpec{}, 8, 8, 5);
  // 4 x 4 samples sit 1/8 px from the edges, never on them.
  const Supersampling aa{.spatial = 4, .views = 2};
  const float coverage[8] = {0, 0, 0.75f, 1, 1, 0.75f, 0, 0};
  for (const char* spec : {"svr", "svr-layered", "deferred", "mvr:cpu", "mvr:exact", "mvr:strip", "mvr:quad",
                           "interp:dual", "warp:dual"}) {
    auto renderer = makeRenderer(parseBackendSpec(spec), scene, PixelType::U8);
    const test::CaptureSink out = renderFiltered(*renderer, cam, aa);
    ASSERT_EQ(out.views.size(), 5u) << spec;
    for (const auto& [key, img] : out.views) {
      ASSERT_EQ(img.width, 8);
      for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) {
          const glm::vec4 c = img.pixel(x, y);
          const float want = coverage[x] * coverage[y];
          EXPECT_NEAR(c.a, want, 1.0f / 255) << spec << " view " << key.second << " pixel " << x << "," << y;
          if (want > 0) {
            EXPECT_NEAR(c.r, 0.8f, 1.5f / 255) << spec << " pixel " << x << "," << y;
          }
        }
    }
  }
}

TEST_F(Antialiasing, WithoutSamplesEdgesAreHard) {
  const Scene scene = edgeQuad();
  const ShearingCamera cam(CameraSpec{}, 8, 8, 3);
  auto svr = makeRenderer(parseBackendSpec("svr"), scene, PixelType::U8);
  const test::CaptureSink out = renderFiltered(*svr, cam, {});
  for (int x = 0; x < 8; ++x) EXPECT_TRUE(out.views.at({0, 1}).row(4)[x * 4 + 3] % 255 == 0) << x;
}

// The comparison stays fair: supersampled alike, MVR meets SVR within the
// tolerances of the unfiltered comparison (mvr_vs_svr_test.cpp).
TEST_F(Antialiasing, MvrMatchesSvrWhenBothAreSupersampled) {
  const Scene scene = loadScene(test::assetPath("default.json"));
  const ShearingCamera cam(*scene.camera, 64, 48, 5);
  const Supersampling aa{.spatial = 2, .views = 2};
  auto svr = makeRenderer(parseBackendSpec("svr"), scene, PixelType::U8);
  const test::CaptureSink reference = renderFiltered(*svr, cam, aa);
  int partial = 0;
  for (const auto& [key, img] : reference.views)
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) partial += img.row(y)[x * 4 + 3] % 255 != 0;
  EXPECT_GT(partial, 5 * 40) << "silhouettes are filtered";
  for (const char* spec : {"mvr:cpu", "mvr:exact"}) {
    auto mvr = makeRenderer(parseBackendSpec(spec), scene, PixelType::U8);
    test::expectCloseOnAnyGl(test::compareViews(reference, renderFiltered(*mvr, cam, aa)), 0.995, 40.0, spec);
  }
  auto strip = makeRenderer(parseBackendSpec("mvr:strip"), scene, PixelType::U8);
  EXPECT_GE(test::compareViews(reference, renderFiltered(*strip, cam, aa)).minPsnr, 40.0);
}

}  // namespace
}  // namespace mvr
