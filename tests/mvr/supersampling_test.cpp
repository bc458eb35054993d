// Supersampling by hand: the sample camera's geometry and the box filter.
#include <gtest/gtest.h>

#include <stdexcept>

#include "mvr/error.h"
#include "mvr/frames/supersampling.h"
#include "tests/support/capture_sink.h"

namespace mvr {
namespace {

CameraSpec spec() {
  CameraSpec s;
  s.trackLeft = -1.0, s.trackRight = 1.0;
  return s;
}

TEST(SupersampledCamera, SamplesAverageToTheViewAndPixel) {
  const ShearingCamera cam(spec(), 40, 30, 5);
  const Supersampling aa{.spatial = 4, .views = 3};
  const ShearingCamera ss = supersampledCamera(cam, aa);
  ASSERT_EQ(ss.width(), 160);
  ASSERT_EQ(ss.height(), 120);
  ASSERT_EQ(ss.views(), 15);
  EXPECT_DOUBLE_EQ(ss.planeHeight(), cam.planeHeight());
  EXPECT_NEAR(ss.viewSpacing(), cam.viewSpacing() / 3, 1e-12);
  // View 2's samples are views 6, 7, 8: centred on its eye, spacing s / 3.
  EXPECT_NEAR(ss.viewX(7), cam.viewX(2), 1e-12);
  EXPECT_NEAR(ss.viewX(6), cam.viewX(2) - cam.viewSpacing() / 3, 1e-12);
  // A point at depth: its sample positions, scaled back by S and averaged
  // over the view's samples, are its position in the view (x is linear in
  // the eye's x).
  const glm::dvec3 p(0.3, -0.2, 0.7);
  for (int v = 0; v < 5; ++v) {
    glm::dvec3 mean(0.0);
    for (int k = 0; k < 3; ++k) mean += ss.project(p, v * 3 + k) / 3.0;
    const glm::dvec3 want = cam.project(p, v);
    EXPECT_NEAR(mean.x / 4, want.x, 1e-9) << v;
    EXPECT_NEAR(mean.y / 4, want.y, 1e-9) << v;
  }
}

TEST(SupersampledCamera, ImpossibleSamplingIsAnError) {
  EXPECT_THROW(supersampledCamera(ShearingCamera(spec(), 40, 30, 1), {.spatial = 1, .views = 2}), Error);
  EXPECT_THROW(supersampledCamera(ShearingCamera(spec(), 8192, 30, 4), {.spatial = 4, .views = 1}), Error);
  EXPECT_THROW(supersampledCamera(ShearingCamera(spec(), 40, 30, 40000), {.spatial = 1, .views = 2}), Error);
  // One view with spatial samples only is fine.
  EXPECT_EQ(supersampledCamera(ShearingCamera(spec(), 40, 30, 1), {.spatial = 2}).views(), 1);
}

Image filled(int w, int h, const glm::vec4& c) {
  Image img(w, h, PixelType::F32);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) img.setLinear(x, y, c);
  return img;
}

TEST(SupersampleSink, ViewsWeighColourByAlpha) {
  test::CaptureSink capture;
  SupersampleSink sink(capture, {.spatial = 2, .views = 2}, 2, 1, 1);
  // Output pixel 0 sees samples (0..1, 0..1) of both sample views; pixel 1
  // (2..3, 0..1).
  Image a = filled(4, 2, glm::vec4(0.0f));
  a.setLinear(0, 0, {1, 0, 0, 1});
  a.setLinear(1, 1, {1, 0, 0, 1});
  a.setLinear(2, 0, {0, 1, 0, 1});
  Image b = filled(4, 2, {1, 0, 0, 1});
  b.setLinear(2, 0, {0, 0, 1, 0.5f});
  b.setLinear(3, 0, glm::vec4(0.0f)), b.setLinear(2, 1, glm::vec4(0.0f)), b.setLinear(3, 1, glm::vec4(0.0f));
  sink.putView(0, 1, b);  // any order
  EXPECT_TRUE(capture.views.empty());
  sink.putView(0, 0, a);
  sink.finish();
  ASSERT_EQ(capture.views.size(), 1u);
  const Image& out = capture.views.at({0, 0});
  ASSERT_EQ(out.width, 2);
  ASSERT_EQ(out.height, 1);
  const glm::vec4 p0 = out.linear(0, 0), p1 = out.linear(1, 0);
  EXPECT_FLOAT_EQ(p0.a, 6.0f / 8.0f);  // 2 of a's 4 samples, all of b's
  EXPECT_FLOAT_EQ(p0.r, 1.0f);         // the red object's colour, not darkened
  EXPECT_FLOAT_EQ(p1.a, 1.5f / 8.0f);
  EXPECT_FLOAT_EQ(p1.g, 1.0f / 1.5f);  // green at alpha 1, blue at 0.5
  EXPECT_FLOAT_EQ(p1.b, 0.5f / 1.5f);
}

TEST(SupersampleSink, EpisComeFromSpatialSampleEpisInAnyOrder) {
  test::CaptureSink capture;
  // Output: 1 pixel wide, 2 views, 2 scanlines; input EPIs 2 wide, 4 views.
  SupersampleSink sink(capture, {.spatial = 2, .views = 2}, 1, 2, 2);
  Image half = filled(2, 4, glm::vec4(0.0f));
  for (int v = 0; v < 4; ++v) half.setLinear(0, v, {0.5f, 0.5f, 0.5f, 1});  // left samples covered
  const Image full = filled(2, 4, {0.5f, 0.5f, 0.5f, 1});
  sink.putEpi(0, 3, full);
  sink.putEpi(0, 0, half);
  EXPECT_TRUE(capture.epis.empty());
  sink.putEpi(0, 2, full);
  ASSERT_EQ(capture.epis.count({0, 1}), 1u);
  sink.putEpi(0, 1, half);
  sink.finish();
  const Image& top = capture.epis.at({0, 0});
  ASSERT_EQ(top.width, 1);
  ASSERT_EQ(top.height, 2);
  for (int v = 0; v < 2; ++v) {
    EXPECT_FLOAT_EQ(top.linear(0, v).a, 0.5f);
    EXPECT_FLOAT_EQ(top.linear(0, v).r, 0.5f);
    EXPECT_FLOAT_EQ(capture.epis.at({0, 1}).linear(0, v).a, 1.0f);
  }
}

TEST(SupersampleSink, KeepsThePixelTypeAndFiltersInLinearLight) {
  test::CaptureSink capture;
  SupersampleSink sink(capture, {.spatial = 2}, 1, 1, 1);
  Image in(2, 2, PixelType::Srgb8);
  in.setLinear(0, 0, {1, 1, 1, 1}), in.setLinear(1, 0, {1, 1, 1, 1});
  in.setLinear(0, 1, {0, 0, 0, 1}), in.setLinear(1, 1, {0, 0, 0, 1});
  sink.putView(0, 0, in);
  const Image& out = capture.views.at({0, 0});
  EXPECT_EQ(out.type, PixelType::Srgb8);
  EXPECT_NEAR(out.linear(0, 0).r, 0.5f, 0.003f);  // sRGB 188, not 128
  EXPECT_EQ(out.row(0)[0], 188);
}

TEST(SupersampleSink, MissingSamplesAndWrongSizesAreErrors) {
  test::CaptureSink capture;
  SupersampleSink sink(capture, {.spatial = 2}, 2, 2, 3);
  sink.putEpi(0, 0, filled(4, 3, glm::vec4(1.0f)));
  EXPECT_THROW(sink.finish(), std::logic_error);
  EXPECT_THROW(sink.putView(0, 0, filled(3, 4, glm::vec4(1.0f))), std::logic_error);
}

}  // namespace
}  // namespace mvr
