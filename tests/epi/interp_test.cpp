// The image-based back end: unprojection by hand, segment slices in the
// slice table, identity at a source view, depth peeling, and quality
// against deferred, the pipeline that renders its source views.
// Tolerances (default scene, 120x90, 5 views):
//  identity     the centre view of `center` equals deferred's exactly
//  dual         >= 24 dB against deferred in every view (silhouettes
//               dilate by up to half a pixel plus the overlap); better than
//               center at the ends of the track (content center never saw)
#include <gtest/gtest.h>

#include "epi/interp_renderer.h"
#include "mvr/error.h"
#include "mvr/scene_io.h"
#include "mvr/source_layers.h"
#include "slicing/image_slices.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

TEST(ImageSlices, UnprojectInvertsTheCamera) {
  CameraSpec spec;
  spec.distance = 5, spec.planeWidth = 3, spec.nearDistance = 2, spec.farDistance = 9;
  spec.trackLeft = -2, spec.trackRight = 2;
  ShearingCamera cam(spec, 64, 48, 5);
  const glm::dvec3 p(0.4, -0.3, 1.1);
  for (int view : {0, 3}) {
    const glm::dvec3 w = cam.project(p, view);
    const glm::dvec3 q = cam.unprojectAt(cam.viewX(view), 0.0, w);
    EXPECT_NEAR(glm::length(q - p), 0.0, 1e-9);
  }
}

TEST(ImageSlices, APixelOnTheImagePlaneStaysPutAndOneInFrontMoves) {
  CameraSpec spec;
  spec.distance = 4, spec.planeWidth = 2, spec.nearDistance = 1, spec.farDistance = 8;
  spec.trackLeft = -1, spec.trackRight = 1;
  ShearingCamera cam(spec, 16, 4, 3);
  // Two pixels of scanline 1 seen from the middle: one on the image plane
  // (zero disparity), one at Z = 2 (moves -(W/Wp) Z/(D - Z) = -8 px per unit).
  SourceLayer layer;
  layer.eye = {0.0, 0.0};
  layer.color = Image(16, 4, PixelType::F32);
  layer.depth.assign(16 * 4, 0.0f);
  auto depthAt = [&](double Z) { return cam.project({0.0, 0.0, Z}, 0).z; };
  layer.depth[1 * 16 + 5] = float(depthAt(0.0));
  layer.depth[1 * 16 + 9] = float(depthAt(2.0));
  const ImageSlices s = sliceSourceLayers({layer}, cam, 0, 0.0f);
  ASSERT_EQ(s.table.sliceCount(), 2u);
  ASSERT_EQ(s.table.scanline(1).size(), 2u);
  auto [a0, a1] = sliceEnds(s.vertices, s.table.scanline(1)[0]);
  auto [b0, b1] = sliceEnds(s.vertices, s.table.scanline(1)[1]);
  // Row coordinate r: x = x0 + (r - 0.5) dx; view 1 (the middle) at r = 1.5.
  EXPECT_NEAR(a0.x0 + a0.dx, 5.0f, 1e-4f);
  EXPECT_NEAR(a1.x0 + a1.dx, 6.0f, 1e-4f);
  EXPECT_NEAR(a0.dx, 0.0f, 1e-5f);
  EXPECT_NEAR(b0.x0 + b0.dx, 9.0f, 1e-4f);
  EXPECT_NEAR(b0.dx, -8.0f, 1e-4f);  // one unit of track per view
  EXPECT_NEAR(b1.x0 - b0.x0, 1.0f, 1e-4f);  // the same width in every view
}

class InterpTest : public test::GlTest {};

TEST_F(InterpTest, DepthPeelingFindsTheLayersBehindAndStops) {
  Scene scene = loadScene(test::assetPath("default.json"));
  ShearingCamera cam(*scene.camera, 96, 72, 5);
  auto sources = makeSourceLayerRenderer(scene);
  RenderStats stats;
  const double track = cam.spec().trackRight - cam.spec().trackLeft;
  const std::vector<SourceLayer> layers = sources->render(cam, {0.0, 0.0}, 8, track, stats);
  // A closed cup: front wall, inside, back wall... then nothing.
  ASSERT_GE(layers.size(), 2u);
  ASSERT_LT(layers.size(), 8u);
  for (size_t k = 1; k < layers.size(); ++k) {
    EXPECT_LT(layers[k].fragments, layers[k - 1].fragments);
    for (size_t i = 0; i < layers[k].depth.size(); ++i)
      if (layers[k].depth[i] > 0.0f) {
        ASSERT_GT(layers[k - 1].depth[i], layers[k].depth[i]);  // reversed Z: in front is larger
      }
  }
  // A track narrower than a pixel's footprint can show nothing behind.
  EXPECT_EQ(sources->render(cam, {0.0, 0.0}, 8, 1e-6, stats).size(), 1u);
}

TEST_F(InterpTest, SourceViewIsReproducedAndDualBeatsCenterAtTheEnds) {
  Scene scene = loadScene(test::assetPath("default.json"));
  ShearingCamera cam(*scene.camera, 120, 90, 5);
  auto deferred = makeDeferredRenderer(scene, PixelType::U8);
  const test::CaptureSink reference = test::renderViews(*deferred, cam);
  auto center = makeInterpRenderer(scene, PixelType::U8, {Acquire::Center, 4, PstMode::Quad});
  auto dual = makeInterpRenderer(scene, PixelType::U8, {Acquire::Dual, 4, PstMode::Quad});
  RenderStats stats;
  const test::CaptureSink c = test::renderViews(*center, cam, stats);
  EXPECT_EQ(stats.counters["source_views"], 1);
  EXPECT_GE(stats.counters["layers"], 2);
  EXPECT_EQ(compareImages(reference.views.at({0, 2}), c.views.at({0, 2})).identicalFraction, 1.0);
  const test::CaptureSink d = test::renderViews(*dual, cam);
  for (int v = 0; v < 5; ++v) {
    const double pd = compareImages(reference.views.at({0, v}), d.views.at({0, v})).psnr;
    EXPECT_GE(pd, 24.0) << v;
    if (v == 0 || v == 4)
      EXPECT_GT(pd, compareImages(reference.views.at({0, v}), c.views.at({0, v})).psnr) << v;
  }
  // The CPU span rasterizer draws the same slices.
  auto cpu = makeInterpRenderer(scene, PixelType::U8, {Acquire::Dual, 4, PstMode::Cpu});
  EXPECT_GE(test::compareViews(d, test::renderViews(*cpu, cam)).minPsnr, 35.0);
}

TEST_F(InterpTest, OneViewAndBadOptions) {
  Scene scene = loadScene(test::assetPath("default.json"));
  ShearingCamera one(*scene.camera, 40, 30, 1);
  auto dual = makeInterpRenderer(scene, PixelType::U8, {Acquire::Dual, 2, PstMode::Quad});
  RenderStats stats;
  const test::CaptureSink v = test::renderViews(*dual, one, stats);
  EXPECT_EQ(v.views.size(), 1u);
  EXPECT_EQ(stats.counters["source_views"], 1);  // both ends are the one view
  EXPECT_THROW(makeInterpRenderer(scene, PixelType::U8, {Acquire::Dual, 0, PstMode::Quad}), Error);
  EXPECT_THROW(parseAcquire("hierarchical-ish"), Error);
}

}  // namespace
}  // namespace mvr
