// SVR against geometry worked out by hand: the cube's silhouette columns on
// several scanlines of the first, middle and last views, and the lit colour
// of its front face.
#include <gtest/gtest.h>

#include <cmath>

#include "mvr/backends/svr/svr_renderer.h"
#include "mvr/assets/scene_io.h"
#include "tests/support/capture_sink.h"
#include "tests/support/gl_fixture.h"

namespace mvr {
namespace {

// The convex hull of the projected corners cut by the line y = yc: its
// extent is the min and max over all corner-pair segments crossing the line.
std::pair<double, double> silhouette(const ShearingCamera& cam, int view, double yc) {
  std::vector<glm::dvec3> p;
  for (int c = 0; c < 8; ++c)
    p.push_back(cam.project({c & 1 ? 0.5 : -0.5, c & 2 ? 0.5 : -0.5, c & 4 ? 0.5 : -0.5}, view));
  double lo = INFINITY, hi = -INFINITY;
  for (size_t a = 0; a < p.size(); ++a)
    for (size_t b = a + 1; b < p.size(); ++b) {
      if ((p[a].y - yc) * (p[b].y - yc) > 0 || p[a].y == p[b].y) continue;
      double t = (yc - p[a].y) / (p[b].y - p[a].y);
      double x = p[a].x + t * (p[b].x - p[a].x);
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
  return {lo, hi};
}

bool nearPixelCentre(double x) { return std::abs(x - 0.5 - std::round(x - 0.5)) < 1e-3; }

TEST(SvrGolden, CubeSilhouetteColumnsMatchProjection) {
  test::sharedContext();
  Scene scene = loadScene(test::assetPath("cube.json"));
  ShearingCamera cam(*scene.camera, 96, 72, 9);
  auto renderer = makeSvrRenderer(scene, PixelType::U8);
  test::CaptureSink sink;
  RenderStats stats;
  renderer->render(cam, sink, stats);
  ASSERT_EQ(sink.views.size(), 9u);
  int checked = 0;
  for (int view : {0, 4, 8}) {
    const Image& img = sink.views.at({0, view});
    for (int j = 8; j < 72; j += 7) {
      auto [xa, xb] = silhouette(cam, view, j + 0.5);
      int first = -1, last = -1;
      for (int x = 0; x < img.width; ++x)
        if (img.pixel(x, j).a > 0) {
          if (first < 0) first = x;
          last = x;
        }
      if (std::isinf(xa)) {
        EXPECT_EQ(first, -1) << "view " << view << " scanline " << j;
        continue;
      }
      // A pixel is covered when its centre x + 0.5 lies inside [xa, xb).
      if (!nearPixelCentre(xa)) {
        EXPECT_EQ(first, int(std::ceil(xa - 0.5))) << "view " << view << " scanline " << j;
      }
      if (!nearPixelCentre(xb)) {
        EXPECT_EQ(last, int(std::ceil(xb - 0.5)) - 1) << "view " << view << " scanline " << j;
      }
      ++checked;
    }
  }
  EXPECT_GE(checked, 20);
}

TEST(SvrGolden, FrontFaceHasTheLitColour) {
  test::sharedContext();
  Scene scene = loadScene(test::assetPath("cube.json"));
  ShearingCamera cam(*scene.camera, 64, 64, 3);
  auto renderer = makeSvrRenderer(scene, PixelType::U8);
  test::CaptureSink sink;
  RenderStats stats;
  renderer->render(cam, sink, stats);
  // Centre pixel of the middle view sees the +z face: normal (0, 0, 1).
  const glm::vec3 l = -glm::normalize(glm::vec3(-0.3f, -0.5f, -1.0f));
  const glm::vec3 expected =
      glm::vec3(0.9f, 0.6f, 0.3f) * (glm::vec3(0.2f) + glm::vec3(0.8f) * l.z);
  const glm::vec4 got = sink.views.at({0, 1}).pixel(32, 32);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 1.0 / 255.0) << "channel " << c;
  EXPECT_EQ(got.a, 1.0f);
}

}  // namespace
}  // namespace mvr
