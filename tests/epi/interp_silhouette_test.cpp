// interp's silhouettes against svr many times finer in x: the finer
// outline's end within half a sample, no covered pixel more than half a
// pixel outside, and scenes no tuning used.
#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include "apps/cli/cli.h"
#include "apps/scenes/test_scenes.h"
#include "mvr/backends/interp/interp_renderer.h"
#include "mvr/error.h"
#include "mvr/assets/scene_io.h"
#include "mvr/views/fragment_lists.h"
#include "mvr/views/source_layers.h"
#include "slicing/image_slices.h"
#include "tests/support/meshes.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

class InterpSilhouette : public test::GlTest {};

// How far outside the true silhouette a covered pixel's centre lies, along
// its scanline: 0 where the reference covers the centre, else the distance
// to the nearest covered sample of a reference `factor` times finer in x
// (samples at (i + 0.5) / factor), in pixels; infinity when none is on the row.
double outsideDistance(const Image& fine, int factor, int x, int y) {
  const double centre = x + 0.5;
  double best = INFINITY;
  for (int i = 0; i < fine.width; ++i)
    if (fine.row(y)[i * 4 + 3] != 0) best = std::min(best, std::abs((i + 0.5) / factor - centre));
  return best;
}

// The worst distance, over every view, of an interp pixel's centre outside
// the true silhouette, and how many lie more than half a pixel out, against
// svr 16 times finer in x.
struct Outside {
  double worst = 0.0;
  long beyondHalf = 0;
};
Outside outsideTheSilhouette(const Scene& scene, const ShearingCamera& cam, Acquire acquire) {
  constexpr int kFactor = 16;
  CameraSpec fineSpec = cam.spec();
  fineSpec.planeHeight = cam.planeHeight();
  const ShearingCamera fine(fineSpec, cam.width() * kFactor, cam.height(), cam.views());
  const test::CaptureSink reference = test::renderViews(*makeSvrRenderer(scene, PixelType::U8), fine);
  const test::CaptureSink got =
      test::renderViews(*makeInterpRenderer(scene, PixelType::U8, {.acquire = acquire, .mode = PstMode::Cpu}), cam);
  Outside out;
  for (const auto& [key, img] : got.views)
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        if (img.row(y)[x * 4 + 3] == 0) continue;
        const double d = outsideDistance(reference.views.at(key), kFactor, x, y);
        out.worst = std::max(out.worst, d);
        out.beyondHalf += d > 0.5 + 0.5 / kFactor;
      }
  return out;
}

// The finer outline (issue 18): at 4 samples a pixel, a silhouette
// pixel's outline end lies within half a sample of the true silhouette
// (svr 16 times finer in x, through the source's own eye), within its
// pixel or over the empty neighbour's near half.
TEST_F(InterpSilhouette, TheFinerOutlineFindsTheSilhouetteWithinHalfASample) {
  const Scene sphere = test::sphereScene(0.6f, 48, 96);
  const ShearingCamera cam(cameraFor(sphere, 80, 60), 80, 60, 9);
  constexpr int kFactor = 16;
  CameraSpec fineSpec = cam.spec();
  fineSpec.planeHeight = cam.planeHeight();
  const ShearingCamera fine(fineSpec, cam.width() * kFactor, cam.height(), cam.views());
  const test::CaptureSink reference = test::renderViews(*makeSvrRenderer(sphere, PixelType::U8), fine);
  const Image& truth = reference.views.at({0, 0});
  RenderStats stats;
  const double track = cam.spec().trackRight - cam.spec().trackLeft;
  const std::vector<SourceLayer> layers =
      makeSourceLayerRenderer(sphere, false, 4)->render(cam, {cam.viewX(0), cam.rowY(0)}, 1, track, stats);
  ASSERT_EQ(layers.size(), 1u);
  const SourceLayer& front = layers[0];
  int rows = 0, beyond = 0;
  for (int y = 0; y < cam.height(); ++y) {
    const float* depth = front.depth.data() + size_t(y) * cam.width();
    int first = 0, last = cam.width() - 1;
    while (first < cam.width() && depth[first] == 0.0f) ++first;
    while (last >= 0 && depth[last] == 0.0f) --last;
    int c0 = 0, c1 = truth.width - 1;
    while (c0 < truth.width && truth.row(y)[c0 * 4 + 3] == 0) ++c0;
    while (c1 >= 0 && truth.row(y)[c1 * 4 + 3] == 0) --c1;
    if (last - first < 2 || c1 - c0 < 2 * kFactor) continue;
    ++rows;
    const PixelOutline& l = front.outline[size_t(y) * cam.width() + first];
    const PixelOutline& r = front.outline[size_t(y) * cam.width() + last];
    // The true edges, between a covered fine sample and the next one out.
    EXPECT_NEAR(first + l.left, double(c0) / kFactor, 0.125 + 0.5 / kFactor) << "row " << y;
    EXPECT_NEAR(last + r.right, double(c1 + 1) / kFactor, 0.125 + 0.5 / kFactor) << "row " << y;
    EXPECT_GE(l.left, -0.5f);
    EXPECT_LE(r.right, 1.5f);
    beyond += (l.left < 0.0f) + (r.right > 1.0f);
  }
  EXPECT_GT(rows, 30);
  EXPECT_GT(beyond, 10);  // ends over the empty neighbour: about half of them
}

// Issue 18: no interp pixel more than half a pixel outside the true
// silhouette, on a cube, a sphere and thin bars before a deep box.
TEST_F(InterpSilhouette, NoPixelMoreThanHalfAPixelOutsideTheSilhouette) {
  const Scene cube = loadScene(test::assetPath("cube.json"));
  const Scene sphere = test::sphereScene(0.6f, 48, 96);
  const Scene thin = app::makeThinAndDeepScene();
  const std::pair<const char*, const Scene*> scenes[] = {{"cube", &cube}, {"sphere", &sphere}, {"thin-deep", &thin}};
  for (const auto& [name, scene] : scenes) {
    const ShearingCamera cam(scene->camera ? *scene->camera : cameraFor(*scene, 80, 60), 80, 60, 9);
    for (Acquire acquire : {Acquire::Dual, Acquire::Hierarchical}) {
      const Outside o = outsideTheSilhouette(*scene, cam, acquire);
      EXPECT_EQ(o.beyondHalf, 0) << name << " " << int(acquire) << ": worst " << o.worst;
      RecordProperty(std::string(name) + "_worst_outside_px", std::to_string(o.worst));
    }
  }
}

// Scenes interp was not tuned on (issue 18). The scanned bunny comes from
// Debian's glmark2-data (GPL, not in the repo): skipped where absent.
// Thresholds are today's figures less a margin. These are linear 8-bit
// images; issue 18's target (32 dB on the bunny at 160x120) is measured on
// what mvr render writes, sRGB-encoded, where the same views score lower
// (31.2 dB) and the target is not met: docs/BENCHMARKS.md.
TEST_F(InterpSilhouette, ScenesItWasNotTunedOn) {
  struct Case {
    const char* name;
    Scene scene;
    double minPsnr;
    double halvesGain;   // dB drawing each half from its near source's layers adds at least
    double outlineGain;  // dB the sources' finer outlines add at least
    double blendGain;    // dB blending adds at least (negative: loses at most)
  };
  std::vector<Case> cases;
  // Bars thinner than a pixel: svr drops or keeps them by where pixel
  // centres fall, so an image-based view differs from it whole bars at a
  // time. Measured (llvmpipe): thin-deep 16.3 dB, 15.9 with outlines at the
  // pixels' boundaries, 16.2 over the whole track, blending 16.7-16.8;
  // bunny 33.8 dB (31.7 before the outlines ran over the empty neighbour,
  // joined pixels shared their ends and the layers behind were inset),
  // 33.0 with all layers over the whole track, 31.2 with outlines at the
  // pixels' boundaries, blending (whole track) 33.6.
  cases.push_back({"thin-deep", app::makeThinAndDeepScene(), 16.0, -0.1, 0.3, 0.2});
  const char* bunny = "/usr/share/glmark2/models/bunny.obj";
  if (std::filesystem::exists(bunny)) cases.push_back({"bunny", app::loadInputScene(bunny, false), 33.3, 0.5, 1.3, -0.6});
  for (const Case& c : cases) {
    const ShearingCamera cam(cameraFor(c.scene, 160, 120), 160, 120, 16);
    const test::CaptureSink svr = test::renderViews(*makeSvrRenderer(c.scene, PixelType::U8), cam);
    const test::CaptureSink dual = test::renderViews(*makeInterpRenderer(c.scene, PixelType::U8, {}), cam);
    const test::SetDifference d = test::compareViews(svr, dual);
    EXPECT_GE(d.minPsnr, c.minPsnr) << c.name;
    RecordProperty(std::string(c.name) + "_dual_min_psnr_db", std::to_string(d.minPsnr));
    const test::CaptureSink whole = test::renderViews(*makeInterpRenderer(c.scene, PixelType::U8, {.halves = false}), cam);
    const double wholePsnr = test::compareViews(svr, whole).minPsnr;
    RecordProperty(std::string(c.name) + "_whole_min_psnr_db", std::to_string(wholePsnr));
    EXPECT_GE(d.minPsnr, wholePsnr + c.halvesGain) << c.name;
    // Silhouette slices end where the surface does within their pixels.
    const test::CaptureSink coarse =
        test::renderViews(*makeInterpRenderer(c.scene, PixelType::U8, {.outlineSamples = 1}), cam);
    const double coarsePsnr = test::compareViews(svr, coarse).minPsnr;
    RecordProperty(std::string(c.name) + "_coarse_min_psnr_db", std::to_string(coarsePsnr));
    EXPECT_GE(d.minPsnr, coarsePsnr + c.outlineGain) << c.name;
    // At a source view nothing is drawn where the source saw nothing.
    for (int v : {0, 15}) EXPECT_EQ(compareImages(svr.views.at({0, v}), dual.views.at({0, v})).extras, 0) << c.name << " " << v;
    // Blending weights the two outlines' disagreement and mixes one
    // surface seen twice, with rims fitted where no finer outline is; on
    // the bunny it now trails the halves it cannot use.
    for (Blend blend : {Blend::Track, Blend::Angular}) {
      const InterpOptions options{.blend = blend};
      const test::CaptureSink b = test::renderViews(*makeInterpRenderer(c.scene, PixelType::U8, options), cam);
      const test::SetDifference bd = test::compareViews(svr, b);
      RecordProperty(std::string(c.name) + "_" + nameOf(kBlendNames, blend) + "_min_psnr_db", std::to_string(bd.minPsnr));
      EXPECT_GE(bd.minPsnr, d.minPsnr + c.blendGain) << c.name << " " << nameOf(kBlendNames, blend);
      for (int v : {0, 15}) {
        EXPECT_LE(compareImages(dual.views.at({0, v}), b.views.at({0, v})).maxError, 1e-6) << c.name << " " << v;
      }
    }
    // More sources, each interval from its own two: no worse than dual
    // (across the whole track, 9 sources on the bunny scored 18.6 dB).
    InterpOptions many{.acquire = Acquire::Hierarchical, .budget = 5, .holeFraction = -1.0};
    RenderStats stats;
    const test::CaptureSink h = test::renderViews(*makeInterpRenderer(c.scene, PixelType::U8, many), cam, stats);
    EXPECT_EQ(stats.counters["source_views"], 5) << c.name;
    const double hPsnr = test::compareViews(svr, h).minPsnr;
    RecordProperty(std::string(c.name) + "_five_sources_min_psnr_db", std::to_string(hPsnr));
    EXPECT_GE(hPsnr, d.minPsnr - 0.3) << c.name;
  }
  if (cases.size() < 2) GTEST_SKIP() << bunny << " absent (Debian's glmark2-data)";
}

}  // namespace
}  // namespace mvr
