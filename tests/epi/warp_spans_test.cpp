// The CPU warp (mvr/backends/warp/warp_spans.h): a plane's known track, the composite's
// weight from the angles at the surface, and the scene back end against
// the GL warp and svr.
#include <gtest/gtest.h>

#include <cmath>

#include "mvr/backends/backend.h"
#include "mvr/backends/warp/depth_warp.h"
#include "mvr/backends/warp/warp_spans.h"
#include "mvr/assets/scene_io.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

constexpr float kTau = 0.02f, kA = 30.0f;

// Distance 4, image plane 2 wide: W / Wp = 8 pixels per unit at 16
// pixels across; 3 views at camera x -1, 0 and 1.
ShearingCamera smallCamera() {
  CameraSpec spec;
  spec.distance = 4, spec.planeWidth = 2, spec.trackLeft = -1, spec.trackRight = 1;
  spec.nearDistance = 0.5, spec.farDistance = 20;
  return ShearingCamera(spec, 16, 8, 3);
}

// A reference at view `view` of cam: every pixel at camera z `depth`,
// coloured by `color(x)`.
template <class Color>
RgbdView plane(const ShearingCamera& cam, int view, float depth, Color&& color) {
  RgbdView r;
  r.color = Image(cam.width(), cam.height(), PixelType::F32);
  r.depth = DepthImage(cam.width(), cam.height());
  for (int y = 0; y < cam.height(); ++y)
    for (int x = 0; x < cam.width(); ++x) {
      r.color.setLinear(x, y, color(x));
      r.depth.at(x, y) = depth;
    }
  r.K = cam.intrinsics(view);
  r.V = cam.worldToCamera(view);
  return r;
}

Image epiOf(const WarpSpans& spans, const ShearingCamera& cam, int scanline) {
  Image epi(cam.width(), cam.views(), PixelType::F32);
  spans.fillEpi(scanline, PixelRows(epi));
  return epi;
}

// A plane at camera z 2, halfway to the image plane, moves (W / Wp)
// (1 - D / z) = -8 pixels per unit of camera x: by hand, view 0 (x = -1)
// shows reference pixel p - 8 at pixel p and nothing left of pixel 8,
// view 2 (x = 1) pixel p + 8 and nothing from pixel 8 on.
TEST(WarpSpans, APlaneMovesAlongItsTrack) {
  const ShearingCamera cam = smallCamera();
  WarpSpans spans(cam, 0, PixelType::F32, kTau, kA);
  spans.add(plane(cam, 1, 2.0f, [](int x) { return glm::vec4(0.0f, 0.0f, x / 16.0f, 1.0f); }), cam.viewX(1));
  const Image epi = epiOf(spans, cam, 3);
  for (int p = 0; p < 16; ++p) {
    const glm::vec4 left = epi.pixel(p, 0), middle = epi.pixel(p, 1), right = epi.pixel(p, 2);
    EXPECT_FLOAT_EQ(middle.b, p / 16.0f) << p;
    EXPECT_FLOAT_EQ(left.a, p >= 8 ? 1.0f : 0.0f) << p;
    if (p >= 8) {
      EXPECT_NEAR(left.b, (p - 8) / 16.0f, 1e-6f) << p;
    }
    EXPECT_FLOAT_EQ(right.a, p < 8 ? 1.0f : 0.0f) << p;
    if (p < 8) {
      EXPECT_NEAR(right.b, (p + 8) / 16.0f, 1e-6f) << p;
    }
  }
}

// A strip over pixels 2 to 9 of every row whose source measured its
// silhouette inside its end pixels (RgbdView::ends): from x = 2.2 to 10.3
// (into empty pixel 10's near half). At camera z 4 / (1 - 0.35 / 8) it
// moves 0.35 pixels per unit of camera x, so by hand view 2 (x = 1) holds
// [2.55, 10.65): pixel centres 3.5 to 10.5. Without the ends the end
// pixels keep their footprints, [2.35, 10.35): pixels 2 to 9; and so
// does an end whose depth leaves the pixel's surface.
TEST(WarpSpans, SilhouettesEndWhereTheSourceMeasuredThem) {
  const ShearingCamera cam = smallCamera();
  const float z = 4.0f / (1.0f - 0.35f / 8.0f);
  auto strip = [&](float rightZ) {
    RgbdView r = plane(cam, 1, z, [](int) { return glm::vec4(1); });
    r.ends.resize(r.depth.values.size());
    for (int y = 0; y < cam.height(); ++y) {
      for (int x = 0; x < cam.width(); ++x)
        if (x < 2 || x > 9) r.depth.at(x, y) = 0.0f;
      r.ends[size_t(y) * cam.width() + 2] = {0.2f, z, 1.0f, z};
      r.ends[size_t(y) * cam.width() + 9] = {0.0f, z, 1.3f, rightZ};
    }
    return r;
  };
  auto covered = [&](RgbdView r, bool withEnds) {
    if (!withEnds) r.ends.clear();
    WarpSpans spans(cam, 0, PixelType::F32, kTau, kA);
    spans.add(std::move(r), cam.viewX(1));
    const Image epi = epiOf(spans, cam, 4);
    std::vector<int> pixels;
    for (int p = 0; p < 16; ++p)
      if (epi.pixel(p, 2).a > 0.0f) pixels.push_back(p);
    return pixels;
  };
  EXPECT_EQ(covered(strip(z), true), (std::vector<int>{3, 4, 5, 6, 7, 8, 9, 10}));
  EXPECT_EQ(covered(strip(z), false), (std::vector<int>{2, 3, 4, 5, 6, 7, 8, 9}));
  EXPECT_EQ(covered(strip(1.5f * z), true), (std::vector<int>{3, 4, 5, 6, 7, 8, 9}));
}

// Two references on the image plane (no disparity), red at x = -1 and
// blue at x = 1, composited at x = 0: each pixel's weight is warpWeight's
// at the angles its surface point makes with the eye and the references,
// computed here from the 3D points with acos in double precision.
TEST(WarpSpans, TheBlendFollowsTheAnglesAtTheSurface) {
  const ShearingCamera cam = smallCamera();
  WarpSpans spans(cam, 0, PixelType::F32, kTau, kA);
  spans.add(plane(cam, 0, 4.0f, [](int) { return glm::vec4(1, 0, 0, 1); }), cam.viewX(0));
  spans.add(plane(cam, 2, 4.0f, [](int) { return glm::vec4(0, 0, 1, 1); }), cam.viewX(2));
  EXPECT_EQ(spans.pairOf(1), std::pair(0, 1));
  EXPECT_EQ(spans.pairOf(0), std::pair(0, -1));
  const glm::dmat4 toWorld = RgbdView::pixelToWorld(cam.intrinsics(1), cam.worldToCamera(1));
  auto angle = [](glm::dvec3 p, glm::dvec3 a, glm::dvec3 b) {
    return std::acos(glm::dot(glm::normalize(a - p), glm::normalize(b - p)));
  };
  for (int j : {0, 5}) {
    const Image epi = epiOf(spans, cam, j);
    for (int p = 0; p < 16; ++p) {
      const glm::dvec3 at = glm::dvec3(toWorld * glm::dvec4(4.0 * (p + 0.5), 4.0 * (j + 0.5), 4.0, 1.0));
      const float w = warpWeight(float(angle(at, cam.eye(1), cam.eye(0))), float(angle(at, cam.eye(1), cam.eye(2))),
                                 4.0f, 4.0f, 0.0f, 0.0f, kTau, kA);
      const glm::vec4 got = epi.pixel(p, 1);
      EXPECT_NEAR(got.r, w, 2e-5f) << p << "," << j;
      EXPECT_NEAR(got.b, 1.0f - w, 2e-5f) << p << "," << j;
      EXPECT_FLOAT_EQ(epi.pixel(p, 0).r, 1.0f);  // at a reference, that reference alone
      EXPECT_FLOAT_EQ(epi.pixel(p, 2).b, 1.0f);
    }
    // Left of the middle the stretch of track from the eye to the red
    // reference faces the surface point squarely and subtends the larger
    // angle, so red weighs less there, not more.
    EXPECT_LT(epi.pixel(0, 1).r, 0.5f);
    EXPECT_GT(epi.pixel(15, 1).r, 0.5f);
  }
}

TEST(WarpSpans, ReferencesOfAnotherSizeAreRefused) {
  const ShearingCamera cam = smallCamera();
  WarpSpans spans(cam, 0, PixelType::U8, kTau, kA);
  RgbdView small = plane(cam, 0, 4.0f, [](int) { return glm::vec4(1); });
  small.depth = DepthImage(8, 8);
  EXPECT_THROW(spans.add(std::move(small), 0.0), Error);
  Image epi(cam.width(), cam.views(), PixelType::U8);
  EXPECT_THROW(spans.fillEpi(0, PixelRows(epi)), Error);  // no references
}

class WarpOnTheCpu : public test::GlTest {};

// The scene back end: the same sources as the GL warp, warped exactly
// instead of through merged grid cells. At the track's ends both are the
// source itself; between, they agree closely and match svr as well.
// Measured on llvmpipe (default scene, 128x96 x 9), with the sources'
// finer outline off (:x1, which the GL grid has no place for): cpu against
// GL 46.5 dB dual, 56.8 hierarchical (5 sources); against svr 31.76 and
// 31.03 dB, as GL's to the hundredth. With it (the default) the CPU's
// silhouettes end inside their pixels: against svr 33.79 and
// 34.92 dB.
TEST_F(WarpOnTheCpu, MatchesTheGlWarpAndSvr) {
  const Scene scene = loadScene(test::assetPath("default.json"));
  const ShearingCamera cam(*scene.camera, 128, 96, 9);
  const test::CaptureSink svr = test::renderViews(*makeSvrRenderer(scene, PixelType::U8), cam);
  for (const char* acquire : {"dual", "hierarchical:b5"}) {
    const std::string spec = std::string("warp:") + acquire;
    RenderStats glStats, cpuStats;
    auto gl = makeRenderer(parseBackendSpec(spec + ":gl"), scene, PixelType::U8);
    auto cpu = makeRenderer(parseBackendSpec(spec + ":x1:cpu"), scene, PixelType::U8);
    auto outlined = makeRenderer(parseBackendSpec(spec + ":cpu"), scene, PixelType::U8);
    EXPECT_EQ(cpu->order(), FrameOrder::Epi);
    const test::CaptureSink a = test::renderViews(*gl, cam, glStats), b = test::renderViews(*cpu, cam, cpuStats);
    const test::SetDifference between = test::compareViews(a, b);
    const double glPsnr = test::compareViews(svr, a).minPsnr, cpuPsnr = test::compareViews(svr, b).minPsnr;
    EXPECT_GE(between.minPsnr, 42.0) << spec;
    EXPECT_GE(cpuPsnr, glPsnr - 0.3) << spec;
    EXPECT_GE(cpuPsnr, 29.0) << spec;
    const double outlinedPsnr = test::compareViews(svr, test::renderViews(*outlined, cam)).minPsnr;
    EXPECT_GE(outlinedPsnr, cpuPsnr + 1.5) << spec;
    EXPECT_EQ(cpuStats.counters["source_views"], glStats.counters["source_views"]) << spec;
    // The ends: each the source itself, within an 8-bit step of the GL
    // warp's identity.
    for (int view : {0, 8}) {
      const ImageDifference d = compareImages(a.views.at({0, view}), b.views.at({0, view}));
      EXPECT_EQ(d.closeFraction, 1.0) << spec << " view " << view;
    }
  }
}

TEST(WarpOnTheCpuOptions, NeedsSourcesItCanPlace) {
  EXPECT_EQ(parseBackendSpec("warp:dual:cpu").warp.path, WarpPath::Cpu);
  EXPECT_EQ(parseBackendSpec("warp:dual:cpu:gl").warp.path, WarpPath::Gl);
  EXPECT_EQ(parseBackendSpec("warp:dual").warp.path, WarpPath::Auto);
  EXPECT_THROW(parseBackendSpec("warp:dual:cpus"), Error);
  // A capture without the track it is to render: the CPU cannot know its rows.
  const ShearingCamera cam = smallCamera();
  std::vector<RgbdView> captured{plane(cam, 0, 4.0f, [](int) { return glm::vec4(1); })};
  EXPECT_THROW(makeWarpRenderer(std::move(captured), PixelType::U8, WarpOptions{.path = WarpPath::Cpu}), Error);
}

}  // namespace
}  // namespace mvr
