// Numerical stability at the extremes (issue 4). Every case renders with
// SVR and with MVR (cpu, exact, strip) and asserts: no crash, no NaN or
// out-of-range value in any float output, and MVR's agreement with SVR.
//
// Agreement here is "within one 8-bit step" (closeFraction), not identity:
// these scenes have colour gradients on strongly foreshortened triangles,
// where llvmpipe's perspective-correct interpolation and the exact
// hyperbolic value land on different sides of a rounding boundary for up to
// about half of the pixels (checked by eye and with a 1% fuzz: only
// silhouette pixels differ by more). Silhouette pixels may differ fully
// (fill rules, sub-pixel snapping): at most 1-2% of a small image.
#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

Scene makeScene(std::vector<glm::vec3> positions, std::vector<glm::uvec3> triangles) {
  Scene s;
  s.positions = std::move(positions);
  s.triangles = std::move(triangles);
  s.colors.resize(s.positions.size());
  for (size_t i = 0; i < s.colors.size(); ++i)
    s.colors[i] = glm::vec3(0.2f + 0.6f * float(i % 3) / 2.0f, 0.3f + 0.5f * float(i % 2), 0.7f);
  s.normals.assign(s.positions.size(), glm::vec3(0, 0, 1));
  s.materialIds.assign(s.triangles.size(), 0);
  Material m;
  m.diffuse = glm::vec3(1.0f);
  s.materials = {m};
  s.ambient = glm::vec3(1.0f);  // unlit: vertex colours as given
  return s;
}

// A grid of quads at several depths, facing the camera.
Scene depthGrid(float scale = 1.0f) {
  std::vector<glm::vec3> p;
  std::vector<glm::uvec3> t;
  for (int k = 0; k < 3; ++k) {
    const float z = (0.8f - 0.9f * k) * scale, x = (-0.8f + 0.6f * k) * scale, h = 0.35f * scale;
    const auto b = unsigned(p.size());
    p.insert(p.end(), {{x - h, -h, z}, {x + h, -h, z}, {x + h, h, z}, {x - h, h, z}});
    t.push_back({b, b + 1, b + 2});
    t.push_back({b, b + 2, b + 3});
  }
  return makeScene(p, t);
}

CameraSpec cameraSpec(float scale = 1.0f, double trackHalfWidth = 1.0) {
  CameraSpec c;
  c.distance = 4.0 * scale;
  c.planeWidth = 3.0 * scale;
  c.trackLeft = -trackHalfWidth * scale;
  c.trackRight = trackHalfWidth * scale;
  c.nearDistance = 1.0 * scale;
  c.farDistance = 9.0 * scale;
  return c;
}

void expectFiniteInRange(const test::CaptureSink& sink, const std::string& what) {
  for (const auto& [key, img] : sink.views) {
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        glm::vec4 v = img.pixel(x, y);
        for (int c = 0; c < 4; ++c)
          ASSERT_TRUE(std::isfinite(v[c]) && v[c] >= 0.0f && v[c] <= 1.0f)
              << what << ": view " << key.second << " pixel " << x << "," << y << " = " << v[c];
      }
  }
}

void expectAgree(const test::SetDifference& d, double close, double psnr = 25.0) {
  EXPECT_GE(d.minClose, close) << "identical " << d.minIdentical << ", PSNR " << d.minPsnr;
  EXPECT_GE(d.minPsnr, psnr) << "close " << d.minClose;
}

// Renders with every mode; returns cpu's agreement with SVR (8-bit).
test::SetDifference checkAll(const Scene& scene, const ShearingCamera& cam, const std::string& what) {
  test::sharedContext();
  for (PstMode mode : {PstMode::Cpu, PstMode::Exact, PstMode::Strip, PstMode::Spans}) {
    auto mvr = makeMvrRenderer(scene, mode, PixelType::F32);
    expectFiniteInRange(test::renderViews(*mvr, cam, PixelType::F32), what + " " + pstModeName(mode));
  }
  auto svrF = makeSvrRenderer(scene, PixelType::F32);
  expectFiniteInRange(test::renderViews(*svrF, cam, PixelType::F32), what + " svr");
  auto svr = makeSvrRenderer(scene, PixelType::U8);
  auto cpu = makeMvrRenderer(scene, PstMode::Cpu, PixelType::U8);
  const test::CaptureSink oracle = test::renderViews(*cpu, cam);
  // GPU spans are the CPU's rule: within one 8-bit step but where a pixel
  // centre lies within the GPU slicer's ulps of a span end (one pixel of
  // the 1728 here over the tiny track on an H100; gpu_spans_test.cpp).
  auto spans = makeMvrRenderer(scene, PstMode::Spans, PixelType::U8);
  const test::SetDifference gpu = test::compareViews(oracle, test::renderViews(*spans, cam));
  EXPECT_GE(gpu.minClose, 0.998) << what << ": spans against cpu, identical " << gpu.minIdentical;
  return test::compareViews(test::renderViews(*svr, cam), oracle);
}

TEST(Extremes, OneTwoAnd4096Views) {
  Scene s = depthGrid();
  for (int n : {1, 2}) {
    auto d = checkAll(s, ShearingCamera(cameraSpec(), 48, 36, n), std::to_string(n) + " views");
    expectAgree(d, 0.99);
  }
  // 4096 views of a small image: EPIs taller than most framebuffers batch.
  ShearingCamera cam(cameraSpec(), 24, 6, 4096);
  auto cpu = makeMvrRenderer(s, PstMode::Cpu, PixelType::U8);
  auto exact = makeMvrRenderer(s, PstMode::Exact, PixelType::U8);
  test::sharedContext();
  const test::CaptureSink oracle = test::renderViews(*cpu, cam);
  auto d = test::compareViews(oracle, test::renderViews(*exact, cam));
  auto spans = makeMvrRenderer(s, PstMode::Spans, PixelType::U8);
  // 144 pixels a view: one that flips is 0.7% of it.
  EXPECT_GE(test::compareViews(oracle, test::renderViews(*spans, cam)).minClose, 0.99) << "spans, 4096 views";
  // 24 x 6 pixels: one silhouette pixel that differs costs 21 dB, and over
  // 4096 views the edges pass within llvmpipe's 1/256-pixel snapping of
  // some pixel centre now and then.
  expectAgree(d, 0.95, 15.0);
}

// Track 1e-6 of the distance: all views (nearly) equal; 1e3: the outer
// views see the scene from far off axis and most of it leaves the image.
TEST(Extremes, TinyAndHugeTracks) {
  Scene s = depthGrid();
  auto tiny = checkAll(s, ShearingCamera(cameraSpec(1.0f, 4e-6), 48, 36, 5), "tiny track");
  expectAgree(tiny, 0.99);
  auto huge = checkAll(s, ShearingCamera(cameraSpec(1.0f, 4e3), 48, 36, 5), "huge track");
  expectAgree(huge, 0.98);
}

// Vertices on the near plane, on the image plane, between the camera and
// near planes, and behind the camera plane: clipping at near/far must
// match GL's (which clips in clip space, the same planes).
TEST(Extremes, GeometryAcrossNearAndCameraPlanes) {
  // Camera plane z = 4, near plane z = 3.
  Scene s = makeScene({{-1.0f, -0.6f, 3.0f},   // on the near plane
                       {1.0f, -0.5f, 0.0f},    // on the image plane
                       {0.2f, 0.7f, 3.5f},     // between near and camera planes
                       {-0.5f, 0.4f, -1.0f},
                       {0.6f, 0.2f, 5.0f},     // behind the camera plane
                       {-0.8f, 0.9f, -2.0f}},
                      {{0, 1, 2}, {3, 1, 4}, {5, 3, 1}});
  auto d = checkAll(s, ShearingCamera(cameraSpec(), 64, 48, 7), "near plane");
  expectAgree(d, 0.98);
}

// A triangle in a plane through view 3's camera: edge-on exactly at that
// view, so its PSTs' i-edges cross there and it faces away on one side.
TEST(Extremes, EdgeOnAtAView) {
  ShearingCamera cam(cameraSpec(), 64, 48, 7);
  const double cx = cam.viewX(3), D = cam.spec().distance;
  auto onPlane = [&](double y, double z) {  // x - cx = 0.3 (z - D)
    return glm::vec3(float(cx + 0.3 * (z - D)), float(y), float(z));
  };
  Scene s = makeScene({onPlane(-0.6, 0.5), onPlane(0.7, 0.2), onPlane(0.1, -1.5)}, {{0, 1, 2}});
  auto d = checkAll(s, cam, "edge-on");
  expectAgree(d, 0.98);
  auto cpu = makeMvrRenderer(s, PstMode::Cpu, PixelType::U8);
  const test::CaptureSink views = test::renderViews(*cpu, cam);  // owns the images
  const Image& edgeOn = views.views.at({0, 3});
  int covered = 0;
  for (int y = 0; y < edgeOn.height; ++y)
    for (int x = 0; x < edgeOn.width; ++x) covered += edgeOn.pixel(x, y).a > 0;
  EXPECT_LE(covered, edgeOn.height) << "an edge-on triangle covers at most a line";
}

TEST(Extremes, ZeroAreaAndRepeatedVertexTriangles) {
  Scene s = makeScene({{-0.5f, -0.5f, 0}, {0.5f, 0.5f, 0}, {0.0f, 0.0f, 0},  // collinear
                       {0.2f, 0.3f, 0.5f}, {-0.7f, 0.1f, -0.5f}},
                      {{0, 1, 2}, {3, 3, 4}, {4, 4, 4}, {0, 1, 4}});
  auto d = checkAll(s, ShearingCamera(cameraSpec(), 48, 36, 5), "degenerate");
  expectAgree(d, 0.99);
}

TEST(Extremes, CoordinatesNear1e6And1eMinus6) {
  for (float scale : {1e6f, 1e-6f}) {
    auto d = checkAll(depthGrid(scale), ShearingCamera(cameraSpec(scale), 48, 36, 5),
                      "scale " + std::to_string(scale));
    expectAgree(d, 0.99);
  }
}

// A triangle far larger than the view volume.
TEST(Extremes, HugeTriangle) {
  Scene s = makeScene({{-1e4f, -1e4f, -0.5f}, {1e4f, -1e4f, 0.5f}, {0.0f, 1e4f, 0.0f}}, {{0, 1, 2}});
  auto d = checkAll(s, ShearingCamera(cameraSpec(), 48, 36, 5), "huge triangle");
  expectAgree(d, 0.99);
}

// A quad larger than every view, split along a diagonal that passes
// through pixel centres in the centre view (square pixels, the image's
// centre a pixel corner). The diagonal is one triangle's long edge and the
// other's short one; their slice ends must be the same float there, or a
// centre on the seam belongs to neither (it did: a crack of 7 pixels at
// 96 x 64 until every edge's parameter took one form). Every pixel of
// every view is covered, in every mode.
TEST(Extremes, SeamThroughPixelCentresLeavesNoCrack) {
  test::sharedContext();
  Scene s = makeScene({{-5, -5, -0.5f}, {5, -5, -0.5f}, {-5, 5, -0.5f}, {5, 5, -0.5f}}, {{0, 1, 3}, {0, 3, 2}});
  const ShearingCamera cam(cameraSpec(), 96, 72, 5);
  for (PstMode mode : {PstMode::Cpu, PstMode::Exact, PstMode::Strip, PstMode::Quad, PstMode::Spans}) {
    auto mvr = makeMvrRenderer(s, mode, PixelType::U8);
    const test::CaptureSink views = test::renderViews(*mvr, cam);
    int uncovered = 0;
    for (const auto& [key, img] : views.views)
      for (int y = 0; y < img.height; ++y)
        for (int x = 0; x < img.width; ++x) uncovered += img.row(y)[x * 4 + 3] != 255;
    EXPECT_EQ(uncovered, 0) << pstModeName(mode);
  }
}

}  // namespace
}  // namespace mvr
