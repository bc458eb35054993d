// The CPU span rasterizer on hand-built slices, including spans that leave
// the EPI on both sides (clipping happens only at the EPI borders).
#include <gtest/gtest.h>

#include "epi/epi_rasterizer.h"
#include "tests/support/capture_sink.h"

namespace mvr {
namespace {

// A camera-facing triangle whose scanline-10 slice runs from x = -20 to 20
// in view 0 and moves 10 pixels right per view (no twist).
ExtremeVertices wideTriangle() {
  ExtremeVertices v;
  auto add = [&](float x, float y) {
    v.x0.push_back(x);
    v.dx.push_back(10.0f);
    v.y.push_back(y);
    v.depth.push_back(0.5f);
    v.invW.push_back(1.0f);
    v.frontOverW.emplace_back(1.0f, 0.5f, 0.25f);
    v.backOverW.emplace_back(0.0f);
  };
  // At y = 10.5 the edge 0-1 is halfway (x = 20), the edge 0-2 at x = -20.
  add(-20.0f, 0.5f), add(60.0f, 20.5f), add(-20.0f, 20.5f);
  v.triangles = {{0, 2, 1}};  // clockwise in y-down pixels: facing the camera
  v.cullBack = {0};
  return v;
}

TEST(SpanRasterizer, SpansAreClippedAtTheEpiBordersOnly) {
  ExtremeVertices v = wideTriangle();
  const int width = 40, views = 5;
  CameraSpec spec;
  ShearingCamera cam(spec, width, 21, views);
  SliceTable table = SliceTable::build(v, 21, 1);
  ASSERT_EQ(table.scanline(10).size(), 1u);
  auto r = makeSpanRasterizer(PixelType::U8);
  test::CaptureSink sink;
  RenderStats stats;
  r->rasterize(v, table, cam, 0, sink, stats);
  const Image& epi = sink.epis.at({0, 10});
  ASSERT_EQ(epi.height, views);
  for (int i = 0; i < views; ++i) {
    const float lo = -20.0f + 10.0f * i, hi = 20.0f + 10.0f * i;
    for (int x = 0; x < width; ++x) {
      const bool inside = x + 0.5f >= lo && x + 0.5f < hi;
      EXPECT_EQ(epi.pixel(x, i).a > 0, inside) << "view " << i << " x " << x;
    }
  }
  // Colour is exact: 1 / w = 1 everywhere, so it is the vertex colour.
  EXPECT_NEAR(epi.pixel(5, 0).g, 128.0f / 255.0f, 1e-6);
}

}  // namespace
}  // namespace mvr
