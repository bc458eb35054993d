// GPU spans (--pst spans) against the CPU spans they reimplement. The
// slice ends come from the GPU's transform and slicer and u from the GPU's
// division, each within a few ulps of the CPU's (the GPU slicer's ends: 4
// ulps of the edge parameter times the edge, slice_table_test.cpp), which
// moves a colour by far less than an 8-bit step. Only where a pixel centre
// lies within those ulps of a span end (1e-4 px over a track ten times the
// distance) can it show another surface: a pixel in thousands at most.
// So: at least 99.9% of pixels within one step, and every one where GL runs
// on the CPU, whose division is the CPU's (llvmpipe: identical sets). On an
// H100: 99.999% identical at 640x480 x 100 views of the teacup, 1 pixel of
// 6912 off over the long track.
#include <gtest/gtest.h>

#include "epi/epi_rasterizer.h"
#include "mvr/backends/backend.h"
#include "mvr/error.h"
#include "mvr/gl/gl_api.h"
#include "mvr/assets/scene_io.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

void expectSpansMatchCpu(const test::SetDifference& d, const std::string& label) {
  EXPECT_GE(d.minClose, 0.999) << label << ", identical " << d.minIdentical;
  if (gl::rendersOnCpu()) {
    EXPECT_EQ(d.minClose, 1.0) << label << ", identical " << d.minIdentical;
  }
}

class GpuSpans : public test::GlTest {
 protected:
  static test::SetDifference againstCpu(const Scene& scene, const ShearingCamera& cam, PixelType type) {
    auto cpu = makeMvrRenderer(scene, PstMode::Cpu, type);
    auto spans = makeMvrRenderer(scene, PstMode::Spans, type);
    return test::compareViews(test::renderViews(*cpu, cam, type), test::renderViews(*spans, cam, type));
  }
};

TEST_F(GpuSpans, EqualTheCpuSpansInEveryPixelType) {
  Scene scene = loadScene(test::assetPath("default.json"));
  const ShearingCamera cam(*scene.camera, 120, 90, 7);
  for (PixelType type : {PixelType::U8, PixelType::Srgb8, PixelType::F32}) {
    const test::SetDifference d = againstCpu(scene, cam, type);
    expectSpansMatchCpu(d, "type " + std::to_string(int(type)));
    // Floats differ in their last bits where bytes round alike: 100 dB is
    // an error of 1e-5, 80 times a float's step at 1.
    if (type == PixelType::F32)
      EXPECT_GE(d.minPsnr, 100.0);
    else
      EXPECT_GE(d.minIdentical, 0.999) << "type " << int(type);
  }
}

// Edges sloping 30 px per view, and a full-parallax grid of rows.
TEST_F(GpuSpans, EqualTheCpuSpansOverALongTrackAndOnAGrid) {
  Scene scene = loadScene(test::assetPath("cube.json"));
  const ShearingCamera grid(*scene.camera, 64, 48, 5, 3);
  expectSpansMatchCpu(againstCpu(scene, grid, PixelType::U8), "grid");
  scene.camera->trackLeft = -5.0 * scene.camera->distance;
  scene.camera->trackRight = 5.0 * scene.camera->distance;
  const ShearingCamera wide(*scene.camera, 96, 72, 5);
  expectSpansMatchCpu(againstCpu(scene, wide, PixelType::U8), "track ten times the distance");
}

// A set in several dispatches fills the same EPIs as one dispatch, byte for
// byte: each EPI is its own work groups' alone.
TEST_F(GpuSpans, BatchesChangeNoByte) {
  Scene scene = loadScene(test::assetPath("default.json"));
  const ShearingCamera cam(*scene.camera, 64, 40, 9);
  auto spans = makeMvrRenderer(scene, PstMode::Spans, PixelType::U8);
  RenderStats one, several;
  const test::CaptureSink whole = test::renderViews(*spans, cam, one);
  setGpuSpanBatchBytes(size_t(64) * 9 * 4 * 3);  // three EPIs per dispatch
  const test::CaptureSink batched = test::renderViews(*spans, cam, several);
  setGpuSpanBatchBytes(size_t(64) << 20);
  EXPECT_EQ(one.counters.at("epis_per_dispatch"), 40);
  EXPECT_EQ(several.counters.at("epis_per_dispatch"), 3);
  EXPECT_EQ(test::compareViews(whole, batched).minIdentical, 1.0);
}

// interp's image slices, each coloured by its own texture vector: on the
// GPU image slicer's path (dual, no blending) and on the host's (blended
// intervals, hierarchical acquisition).
TEST_F(GpuSpans, EqualTheCpuSpansForImageSlices) {
  Scene scene = loadScene(test::assetPath("default.json"));
  const ShearingCamera cam(*scene.camera, 96, 72, 9);
  for (const char* spec : {"interp:dual", "interp:dual:track", "interp:hierarchical:1"}) {
    auto cpu = makeRenderer(parseBackendSpec(std::string(spec) + ":cpu"), scene, PixelType::U8);
    auto spans = makeRenderer(parseBackendSpec(std::string(spec) + ":spans"), scene, PixelType::U8);
    const test::SetDifference d = test::compareViews(test::renderViews(*cpu, cam), test::renderViews(*spans, cam));
    expectSpansMatchCpu(d, spec);
    EXPECT_GE(d.minIdentical, 0.999) << spec;
  }
}

// Scenes that need more than the diffuse pass are refused by name, not
// rendered without their texture or highlights.
TEST_F(GpuSpans, RefuseScenesThatNeedMoreThanDiffuse) {
  Scene scene = loadScene(test::assetPath("mirror.json"));
  try {
    makeMvrRenderer(scene, PstMode::Spans, PixelType::U8);
    FAIL() << "a view-dependent scene was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("spans"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("view-dependent"), std::string::npos) << e.what();
  }
}

// The default a GPU picks (fastestGpuPst) is spans exactly where spans
// render the scene: each choice rendered here, spans or not, and every
// scene and back end that spans refuse gets another mode.
TEST_F(GpuSpans, AreTheGpuDefaultWhereTheyShadeTheScene) {
  struct Case {
    const char* scene;
    const char* backend;
    bool spans;
  };
  for (const Case c : {Case{"default.json", "mvr", true}, {"shiny.json", "mvr", false}, {"textured.json", "mvr", false},
                       {"mirror.json", "mvr", false}, {"default.json", "interp", true}, {"shiny.json", "interp", true},
                       {"shiny.json", "interp:dual:s2", false}, {"default.json", "interp:dual:s2", true},
                       {"textured.json", "interp", true}, {"mirror.json", "interp", true}}) {
    const std::string label = std::string(c.scene) + " " + c.backend;
    const Scene scene = loadScene(test::assetPath(c.scene));
    BackendOptions o = parseBackendSpec(c.backend);
    const PstMode chosen = fastestGpuPst(o, shading::planShading(scene));
    EXPECT_EQ(chosen == PstMode::Spans, c.spans) << label;
    o.setPst(PstMode::Spans);
    bool accepted = true;
    try {
      const ShearingCamera cam(*scene.camera, 32, 24, 3);
      test::renderViews(*makeRenderer(o, scene, PixelType::U8), cam);
    } catch (const Error&) {
      accepted = false;
    }
    EXPECT_EQ(accepted, c.spans) << label;
  }
}

}  // namespace
}  // namespace mvr
