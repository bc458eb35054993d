// The CPU span rasterizer on hand-built slices, including spans that leave
// the EPI on both sides (clipping happens only at the EPI borders).
#include <gtest/gtest.h>

#include "epi/epi_rasterizer.h"
#include "mvr/assets/scene_io.h"
#include "mvr/views/source_layers.h"
#include "shading/lighting.h"
#include "slicing/extreme_vertices.h"
#include "slicing/image_slices.h"
#include "tests/support/capture_sink.h"
#include "tests/support/gl_fixture.h"
#include "tests/support/render_helpers.h"

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

// The row walk, the column walk and the fast diffuse fill are three ways
// to the same spans, each compiled for x86-64 and, where the CPU has it,
// x86-64-v2: every EPI must have the same bytes whichever is taken, in
// every pixel type. The lit teacup over a deep track gives
// slices from under a pixel to dozens of pixels wide, sloped both ways,
// with colour that changes along most of them.
TEST(SpanRasterizer, EveryPathFillsTheSameBytes) {
  Scene scene = loadScene(test::assetPath("default.json"));
  CameraSpec spec = *scene.camera;
  spec.trackLeft *= 3, spec.trackRight *= 3;
  const ShearingCamera cam(spec, 96, 72, 40);
  const ExtremeVertices v = transformToExtremes(scene, shading::litVertexColors(scene), cam, 0);
  const SliceTable table = SliceTable::build(v, cam.height());
  auto render = [&](PixelType type, SpanPaths paths) {
    test::CaptureSink sink;
    RenderStats stats;
    makeSpanRasterizer(type, {}, paths)->rasterize(v, table, cam, 0, sink, stats);
    return sink.epis;
  };
  using Walk = SpanPaths::Walk;
  for (PixelType type : {PixelType::U8, PixelType::Srgb8, PixelType::F32}) {
    const auto reference = render(type, {Walk::Rows, false, true});
    size_t covered = 0;
    for (const auto& [at, epi] : reference)
      for (int i = 0; i < epi.height; ++i)
        for (int x = 0; x < epi.width; ++x) covered += epi.pixel(x, i).a > 0;
    ASSERT_GT(covered, size_t(96 * 72 * 40 / 10)) << "the teacup should fill a good part of the EPIs";
    for (SpanPaths paths : {SpanPaths{Walk::Rows, false}, SpanPaths{Walk::Columns, false},
                            SpanPaths{Walk::Rows, true}, SpanPaths{Walk::Columns, true}, SpanPaths{Walk::Auto, true},
                            SpanPaths{Walk::Auto, true, true}}) {
      const auto epis = render(type, paths);
      ASSERT_EQ(epis.size(), reference.size());
      for (const auto& [at, epi] : reference)
        ASSERT_EQ(epis.at(at).bytes, epi.bytes) << "type " << int(type) << ", walk " << int(paths.walk)
                                                << ", fast " << paths.fastDiffuse << ", baseline "
                                                << paths.baselineIsa << ", scanline " << at.second;
    }
  }
}

// interp's slices carry vectors of their source pixels: one texel for a
// lone pixel (its colour at every u, so the fast fill takes it), more for
// a coalesced run (the general fill). Both fills give the same bytes.
TEST(SpanRasterizer, VectorSlicesFillTheSameBytesOnEveryPath) {
  test::sharedContext();
  const Scene scene = loadScene(test::assetPath("default.json"));
  const ShearingCamera cam(*scene.camera, 96, 72, 24);
  const double track = cam.spec().trackRight - cam.spec().trackLeft;
  RenderStats stats;
  std::vector<SourceLayer> layers;
  for (double x : {cam.viewX(0), cam.viewX(23)})
    for (SourceLayer& l : makeSourceLayerRenderer(scene)->render(cam, {x, 0.0}, 2, track, stats))
      layers.push_back(std::move(l));
  using Walk = SpanPaths::Walk;
  for (float coalesce : {0.0f, 2.0f}) {
    const ImageSlices slices = sliceSourceLayers(layers, cam, 0, {.coalesce = coalesce});
    size_t lone = 0;
    for (const SliceVector& vector : slices.vertices.vectors) lone += vector.length == 1;
    const size_t count = slices.vertices.vectors.size();
    if (coalesce == 0.0f) {
      EXPECT_EQ(lone, count) << "uncoalesced, every slice is one pixel's";
    } else {
      EXPECT_LT(lone, count * 9 / 10) << "coalesced runs should give longer vectors";
    }
    for (PixelType type : {PixelType::U8, PixelType::Srgb8}) {
      auto render = [&](SpanPaths paths) {
        test::CaptureSink sink;
        makeSpanRasterizer(type, {.sliceVectors = true}, paths)
            ->rasterize(slices.vertices, slices.table, cam, 0, sink, stats);
        return sink.epis;
      };
      const auto reference = render({Walk::Rows, false, true});
      for (SpanPaths paths : {SpanPaths{Walk::Rows, true}, SpanPaths{Walk::Columns, true}, SpanPaths{Walk::Auto, true},
                              SpanPaths{Walk::Auto, true, true}})
        for (const auto& [at, epi] : render(paths))
          ASSERT_EQ(epi.bytes, reference.at(at).bytes) << "coalesce " << coalesce << ", type " << int(type)
                                                       << ", walk " << int(paths.walk) << ", scanline " << at.second;
    }
  }
}

}  // namespace
}  // namespace mvr
