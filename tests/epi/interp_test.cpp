// The image-based back end: identity at a source view, depth peeling,
// fragment lists, and quality against deferred, the pipeline that renders
// its source views (image slices by hand: image_slices_test.cpp).
// Tolerances (default scene, 120x90, 5 or 9 views):
//  identity     the centre view of `center` equals deferred's exactly
//  dual         >= 24 dB against deferred in every view (silhouettes
//               dilate by up to half a pixel plus the overlap); better than
//               center at the ends of the track (content center never saw)
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

class InterpTest : public test::GlTest {
 protected:
  // The default scene at 120x90 and its views from deferred, the pipeline
  // that renders interp's source views.
  struct Reference {
    explicit Reference(int viewCount)
        : scene(loadScene(test::assetPath("default.json"))), cam(*scene.camera, 120, 90, viewCount),
          views(test::renderViews(*makeDeferredRenderer(scene, PixelType::U8), cam)) {}
    Scene scene;
    ShearingCamera cam;
    test::CaptureSink views;
  };
};

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

// A plane drawn twice in the same place, red then blue, behind a cube:
// every pixel of the plane a tie of depths that the first drawn wins.
Scene coincidentPlanes() {
  const std::string path = ::testing::TempDir() + "/mvr_coincident_planes.json";
  std::ofstream(path) << R"({"meshes": [
    {"file": ")" << test::assetPath("plane.obj") << R"(", "material": {"diffuse": [0.9, 0.1, 0.1]}},
    {"file": ")" << test::assetPath("plane.obj") << R"(", "material": {"diffuse": [0.1, 0.1, 0.9]}},
    {"file": ")" << test::assetPath("cube.obj") << R"(", "transform": {"translate": [0.2, 0.1, 0.5], "scale": 0.4},
     "material": {"diffuse": [0.8, 0.8, 0.8]}}],
    "lights": [{"type": "directional", "direction": [-0.3, -0.4, -1.0], "color": [0.8, 0.8, 0.8]}],
    "camera": {"distance": 5.0, "image_plane": 3.2, "track": [-1.5, 1.5], "near": 3.0, "far": 7.0}})";
  return loadScene(path);
}

// Ten planes one behind the other, facing the camera: ten fragments a
// pixel, more than the fragment lists first make room for.
Scene stackedPlanes() {
  const std::string path = ::testing::TempDir() + "/mvr_stacked_planes.json";
  std::ofstream json(path);
  json << R"({"meshes": [)";
  for (int k = 0; k < 10; ++k)
    json << (k ? "," : "") << R"({"file": ")" << test::assetPath("plane.obj") << R"(", "transform": {"translate": [0, 0, )"
         << 0.5 - 0.12 * k << R"(], "scale": 3}, "material": {"diffuse": [0.5, )" << 0.1 * k << R"(, 0.5]}})";
  json << R"(], "lights": [{"type": "directional", "direction": [0, 0, -1], "color": [1, 1, 1]}],
    "camera": {"distance": 5.0, "image_plane": 3.2, "track": [-1.5, 1.5], "near": 3.0, "far": 7.0}})";
  json.close();
  return loadScene(path);
}

// The fragment lists' layers are the peel's, bit for bit: each a pass of
// the mesh against one pass resolved per layer, on a scene whose layers
// run deep (the cup: front, inside, back, over the floor), a textured one,
// one of ties and one whose lists outgrow their first room, at two sizes (one not a multiple of llvmpipe's 4x4
// blocks) and from two eyes.
TEST_F(InterpTest, OnePassFindsTheLayersThePeelFinds) {
  for (const auto& [file, fewest] :
       {std::pair<const char*, size_t>{"default.json", 3}, {"textured.json", 2}, {"ties", 2}, {"stack", 6}}) {
    const std::string name = file;
    const Scene scene = name == "ties"    ? coincidentPlanes()
                        : name == "stack" ? stackedPlanes()
                                          : loadScene(test::assetPath(file));
    for (const int size : {96, 173}) {
      ShearingCamera cam(*scene.camera, size, size * 3 / 4, 5);
      const double track = cam.spec().trackRight - cam.spec().trackLeft;
      RenderStats stats;
      for (const glm::dvec2 eye : {glm::dvec2(0.0), glm::dvec2(cam.viewX(0), 0.0)}) {
        const auto peeled =
            makeSourceLayerRenderer(scene, true, 1, Peeling::PassPerLayer)->render(cam, eye, 6, track, stats);
        const auto lists = makeSourceLayerRenderer(scene, true, 1, Peeling::OnePass)->render(cam, eye, 6, track, stats);
        ASSERT_GE(peeled.size(), fewest) << name;
        ASSERT_EQ(lists.size(), peeled.size()) << name;
        for (size_t k = 0; k < peeled.size(); ++k) {
          SCOPED_TRACE(name + ", layer " + std::to_string(k) + ", " + std::to_string(size) + " px");
          EXPECT_EQ(lists[k].depth, peeled[k].depth);
          EXPECT_EQ(lists[k].color.bytes, peeled[k].color.bytes);
          ASSERT_EQ(lists[k].normals.size(), peeled[k].normals.size());
          size_t normalsDiffer = 0;
          for (size_t i = 0; i < peeled[k].normals.size(); ++i)
            normalsDiffer += lists[k].normals[i] != peeled[k].normals[i];
          EXPECT_EQ(normalsDiffer, 0u);
        }
      }
    }
  }
}

// One pass of the mesh a source, a pass a layer where the lists would pass
// their memory limit: the same layers either way.
TEST_F(InterpTest, FragmentListsOverTheirLimitPeelAPassALayer) {
  const Scene scene = stackedPlanes();
  const ShearingCamera cam(*scene.camera, 96, 72, 5);
  const double track = cam.spec().trackRight - cam.spec().trackLeft;
  RenderStats lists, limited, peeled;
  const auto a = makeSourceLayerRenderer(scene)->render(cam, {0.0, 0.0}, 6, track, lists);
  FragmentLists::setMaxBytes(1024);  // the first room holds two fragments a pixel; ten would not fit
  const auto b = makeSourceLayerRenderer(scene)->render(cam, {0.0, 0.0}, 6, track, limited);
  FragmentLists::setMaxBytes(FragmentLists::kMaxBytes);
  const auto c = makeSourceLayerRenderer(scene, false, 1, Peeling::PassPerLayer)->render(cam, {0.0, 0.0}, 6, track, peeled);
  ASSERT_EQ(a.size(), 6u);
  ASSERT_EQ(b.size(), a.size());
  ASSERT_EQ(c.size(), a.size());
  EXPECT_EQ(lists.counters.at("layer_mesh_passes"), 1);
  EXPECT_EQ(limited.counters.at("layer_mesh_passes"), 6);
  EXPECT_EQ(peeled.counters.at("layer_mesh_passes"), 6);
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(b[k].depth, a[k].depth) << "layer " << k;
    EXPECT_EQ(b[k].color.bytes, a[k].color.bytes) << "layer " << k;
    EXPECT_EQ(c[k].depth, a[k].depth) << "layer " << k;
  }
}

TEST_F(InterpTest, SourceViewIsReproducedAndDualBeatsCenterAtTheEnds) {
  const Reference ref(5);
  const Scene& scene = ref.scene;
  const ShearingCamera& cam = ref.cam;
  const test::CaptureSink& reference = ref.views;
  auto center = makeInterpRenderer(scene, PixelType::U8, {Acquire::Center, 4, PstMode::Quad});
  auto dual = makeInterpRenderer(scene, PixelType::U8, {Acquire::Dual, 4, PstMode::Quad});
  RenderStats stats;
  const test::CaptureSink c = test::renderViews(*center, cam, stats);
  EXPECT_EQ(stats.counters["source_views"], 1);
  EXPECT_GE(stats.counters["layers"], 2);
  // The source view is the source's render, by another program than the
  // reference's: GL promises the same bits only to the same shader, so
  // within one 8-bit step (render_helpers.h; identical on llvmpipe, 97.4%
  // identical on an NVIDIA H100).
  EXPECT_LE(compareImages(reference.views.at({0, 2}), c.views.at({0, 2})).maxError, 1.0 / 255.0 + 1e-6);
  const test::CaptureSink d = test::renderViews(*dual, cam);
  for (int v = 0; v < 5; ++v) {
    const double pd = compareImages(reference.views.at({0, v}), d.views.at({0, v})).psnr;
    EXPECT_GE(pd, 24.0) << v;
    if (v == 0 || v == 4) {
      EXPECT_GT(pd, compareImages(reference.views.at({0, v}), c.views.at({0, v})).psnr) << v;
    }
  }
  // The CPU span rasterizer draws the same slices.
  auto cpu = makeInterpRenderer(scene, PixelType::U8, {Acquire::Dual, 4, PstMode::Cpu});
  EXPECT_GE(test::compareViews(d, test::renderViews(*cpu, cam)).minPsnr, 35.0);
}

// Issue 18: at a source view interp's image is the source's, within one
// 8-bit step, in every mode and from either path (GPU-sliced layers and
// layers read back), whatever the other sources' slices would draw there.
TEST_F(InterpTest, DualReproducesBothSourceViewsInEveryMode) {
  const Reference ref(5);
  for (PstMode mode : {PstMode::Quad, PstMode::Strip, PstMode::Exact, PstMode::Cpu})
    for (PstBuilder builder : {PstBuilder::Gpu, PstBuilder::Cpu}) {
      if (mode == PstMode::Cpu && builder == PstBuilder::Gpu) continue;
      const InterpOptions options{.acquire = Acquire::Dual, .mode = mode, .builder = builder};
      RenderStats stats;
      const test::CaptureSink d = test::renderViews(*makeInterpRenderer(ref.scene, PixelType::U8, options), ref.cam, stats);
      for (int v : {0, 4}) {
        const ImageDifference diff = compareImages(ref.views.views.at({0, v}), d.views.at({0, v}));
        EXPECT_LE(diff.maxError, 1.0 / 255.0 + 1e-6) << pstModeName(mode) << " " << stats.notes["image_slicer"] << " view " << v;
      }
      // Between the sources the slices are drawn, not a source.
      EXPECT_LT(compareImages(ref.views.views.at({0, 2}), d.views.at({0, 2})).identicalFraction, 1.0);
    }
}

TEST_F(InterpTest, EveryRowOfViewsReproducesItsOwnSourceView) {
  // Rows of views take turns with the EPI rasterizer, whose target is far
  // taller: each row's source views must still fill their own viewport.
  Scene scene = loadScene(test::assetPath("default.json"));
  CameraSpec spec = *scene.camera;
  spec.rowTop = 0.3, spec.rowBottom = -0.3;
  ShearingCamera cam(spec, 120, 90, 5, 2);
  const test::CaptureSink reference = test::renderViews(*makeDeferredRenderer(scene, PixelType::U8), cam);
  const test::CaptureSink c = test::renderViews(
      *makeInterpRenderer(scene, PixelType::U8, {.acquire = Acquire::Center}), cam);
  for (int row : {0, 1})  // within one 8-bit step, as above
    EXPECT_LE(compareImages(reference.views.at({row, 2}), c.views.at({row, 2})).maxError, 1.0 / 255.0 + 1e-6) << row;
}

TEST_F(InterpTest, CoalescingCutsSlicesAndKeepsTheSourceViewAndQuality) {
  const Reference ref(5);
  const Scene& scene = ref.scene;
  const ShearingCamera& cam = ref.cam;
  const test::CaptureSink& reference = ref.views;
  InterpOptions options{.acquire = Acquire::Center};
  RenderStats each, runs;
  auto plain = makeInterpRenderer(scene, PixelType::U8, options);
  const test::CaptureSink p = test::renderViews(*plain, cam, each);
  options.coalesce = 1.0f;
  auto coalesced = makeInterpRenderer(scene, PixelType::U8, options);
  const test::CaptureSink c = test::renderViews(*coalesced, cam, runs);
  EXPECT_EQ(runs.counters["slice_pixels"], each.counters["slice_pixels"]);
  EXPECT_LT(runs.counters["slices"], 0.5 * each.counters["slices"]);
  // The source view: every pixel read back at its own texel centre.
  EXPECT_GE(compareImages(reference.views.at({0, 2}), c.views.at({0, 2})).closeFraction, 0.999);
  for (int v : {0, 1, 3, 4}) {
    const double pc = compareImages(reference.views.at({0, v}), c.views.at({0, v})).psnr;
    EXPECT_GE(pc, compareImages(reference.views.at({0, v}), p.views.at({0, v})).psnr - 1.0) << v;
  }
  options.mode = PstMode::Cpu;
  auto cpu = makeInterpRenderer(scene, PixelType::U8, options);
  EXPECT_GE(test::compareViews(c, test::renderViews(*cpu, cam)).minPsnr, 35.0);
  options.mode = PstMode::Exact;
  auto exact = makeInterpRenderer(scene, PixelType::U8, options);
  EXPECT_GE(test::compareViews(c, test::renderViews(*exact, cam)).minPsnr, 35.0);
}

// Interp on the GPU (source layers kept in GPU memory, sliced by compute
// passes, PSTs pulled by the vertex shaders, vectors indexed per slice)
// draws what the CPU-sliced, CPU-built geometry draws: at least 99.9% of
// pixels identical, PSNR at least 45 dB, in every mode, with and without
// coalesced runs (vectors longer than a texel, with their MIP chains).
// The visibility filter and hierarchical acquisition's hole counts run as
// compute passes there too: the same layers, hidden pixels, hole checks
// and source views. The filter decides a pixel from the track's parallax
// in double precision, whose division GLSL promises no better than single
// (test::expectSameDecisions, tests/support/gl_fixture.h): off llvmpipe, with
// the filter on, hidden pixels and the slices they leave may differ by one
// in a thousand.
TEST_F(InterpTest, GpuSlicingAndPstsMatchTheCpuPath) {
  Scene scene = loadScene(test::assetPath("default.json"));
  const ShearingCamera small(*scene.camera, 96, 72, 7), large(*scene.camera, 120, 90, 9);
  struct Case {
    Acquire acquire;
    PstMode mode;
    float coalesce;
    bool visibility = false;
    int maxLayers = 4;  // hierarchical: fewer, and larger views, so that the ends leave holes
  };
  std::vector<Case> cases;
  for (PstMode mode : {PstMode::Quad, PstMode::Strip, PstMode::Exact})
    for (float coalesce : {0.0f, 1.0f}) cases.push_back({Acquire::Dual, mode, coalesce});
  cases.push_back({Acquire::Center, PstMode::Quad, 1.0f});
  cases.push_back({Acquire::Center, PstMode::Quad, 0.0f, true});
  cases.push_back({Acquire::Dual, PstMode::Strip, 1.0f, true});
  cases.push_back({Acquire::Hierarchical, PstMode::Quad, 0.0f, false, 1});
  cases.push_back({Acquire::Hierarchical, PstMode::Strip, 1.0f, true, 2});
  for (const Case& c : cases) {
    InterpOptions options{.acquire = c.acquire, .maxLayers = c.maxLayers, .mode = c.mode, .coalesce = c.coalesce,
                          .visibility = c.visibility};
    const ShearingCamera& cam = c.acquire == Acquire::Hierarchical ? large : small;
    options.holeFraction = 0.0;  // hierarchical: a source wherever a hole is left
    options.builder = PstBuilder::Gpu;
    RenderStats gpuStats, cpuStats;
    const auto gpu = test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam, gpuStats);
    options.builder = PstBuilder::Cpu;
    const auto cpu = test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam, cpuStats);
    const std::string label = std::string(acquireName(c.acquire)) + " " + pstModeName(c.mode) + " coalesce " +
                              std::to_string(c.coalesce) + (c.visibility ? " visibility" : "");
    EXPECT_EQ(gpuStats.notes["pst_builder"], "gpu") << label;
    EXPECT_EQ(cpuStats.notes["pst_builder"], "cpu") << label;
    EXPECT_EQ(gpuStats.notes["image_slicer"], "gpu") << label;
    EXPECT_EQ(cpuStats.notes["image_slicer"], "cpu") << label;
    for (const char* counter : {"slices", "slice_pixels", "hidden_pixels"}) {
      const long got = long(gpuStats.counters[counter]), want = long(cpuStats.counters[counter]);
      if (c.visibility)
        test::expectSameDecisions(got, want, want, label + " " + counter);
      else
        EXPECT_EQ(got, want) << label << " " << counter;
    }
    EXPECT_EQ(gpuStats.counters["layers"], cpuStats.counters["layers"]) << label;
    EXPECT_EQ(gpuStats.counters["hole_checks"], cpuStats.counters["hole_checks"]) << label;
    EXPECT_EQ(gpuStats.counters["source_views"], cpuStats.counters["source_views"]) << label;
    if (c.acquire == Acquire::Hierarchical) {
      EXPECT_GT(gpuStats.counters["source_views"], 2) << label;
    }
    if (c.visibility) {
      EXPECT_GT(gpuStats.counters["hidden_pixels"], 0) << label;
    }
    const auto d = test::compareViews(cpu, gpu);
    EXPECT_GE(d.minIdentical, 0.999) << label;
    EXPECT_GE(d.minPsnr, 45.0) << label;
  }
}

long totalHoles(const test::CaptureSink& reference, const test::CaptureSink& b) {
  long holes = 0;
  for (const auto& [key, img] : reference.views) holes += compareImages(img, b.views.at(key)).holes;
  return holes;
}

TEST_F(InterpTest, HierarchicalAddsSourcesWhereTheEndsLeaveHoles) {
  const Reference ref(9);
  const Scene& scene = ref.scene;
  const ShearingCamera& cam = ref.cam;
  const test::CaptureSink& reference = ref.views;
  // One layer per source: the ends alone cannot see behind the cup's rim.
  InterpOptions options{.acquire = Acquire::Dual, .maxLayers = 1};
  const test::CaptureSink dual = test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam);
  options.acquire = Acquire::Hierarchical;
  RenderStats stats;
  const test::CaptureSink h = test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam, stats);
  EXPECT_GT(stats.counters["source_views"], 2);
  EXPECT_LE(stats.counters["source_views"], options.budget);
  EXPECT_GE(stats.counters["hole_checks"], 1);
  EXPECT_LT(totalHoles(reference, h), totalHoles(reference, dual));
  // A budget of two is dual.
  options.budget = 2;
  const test::CaptureSink two = test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam);
  EXPECT_EQ(test::compareViews(dual, two).minIdentical, 1.0);
}

// Intervals (more than two sources) and blending in a split job: each
// share's EPIs are the whole render's, byte for byte.
TEST_F(InterpTest, IntervalsAndBlendingJoinAcrossShares) {
  const Scene scene = loadScene(test::assetPath("default.json"));
  const ShearingCamera cam(*scene.camera, 48, 37, 9);
  const InterpOptions options{
      .acquire = Acquire::Hierarchical, .budget = 4, .blend = Blend::Track, .holeFraction = -1.0};
  auto renderer = makeInterpRenderer(scene, PixelType::U8, options);
  test::CaptureSink whole;
  RenderStats stats;
  renderer->render(cam, whole, stats);
  EXPECT_EQ(stats.counters["source_views"], 4);
  for (IndexRange part : {IndexRange{0, 5}, IndexRange{5, 37}}) {
    RenderShare share = cam.share();
    share.scanlines = part;
    test::CaptureSink got;
    renderer->render(cam.withShare(share), got, stats);
    EXPECT_EQ(got.epis.size(), size_t(part.size()));
    for (const auto& [key, epi] : got.epis) EXPECT_EQ(epi.bytes, whole.epis.at(key).bytes) << "scanline " << key.second;
  }
}

TEST_F(InterpTest, VisibilityDropsHiddenPixelsWithoutOpeningHoles) {
  const Reference ref(5);
  const Scene& scene = ref.scene;
  const ShearingCamera& cam = ref.cam;
  const test::CaptureSink& reference = ref.views;
  InterpOptions options{.acquire = Acquire::Center};
  RenderStats all, visible;
  const test::CaptureSink a = test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam, all);
  options.visibility = true;
  const test::CaptureSink v = test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam, visible);
  EXPECT_GT(visible.counters["hidden_pixels"], 0);
  EXPECT_LT(visible.counters["slices"], all.counters["slices"]);
  EXPECT_LE(totalHoles(reference, v), totalHoles(reference, a));
  EXPECT_GE(test::compareViews(a, v).minPsnr, 40.0);
}

// A specular plane on the image plane under a point light: nothing moves
// between views but the highlight, so every difference from deferred is
// the highlight's.
Scene specularPlane() {
  const std::string path = ::testing::TempDir() + "/mvr_specular_plane.json";
  std::ofstream(path) << R"({"meshes": [{"file": ")" << test::assetPath("plane.obj") << R"(",
    "material": {"diffuse": [0.3, 0.35, 0.4], "specular": [0.8, 0.8, 0.8], "shininess": 30,
                 "specular_model": "phong"}}],
    "lights": [{"type": "point", "position": [0.2, 0.1, 1.2], "color": [1, 1, 1]}],
    "ambient": [0.1, 0.1, 0.1],
    "camera": {"distance": 3.0, "image_plane": 0.8, "track": [-1, 1], "near": 2.0, "far": 4.0}})";
  return loadScene(path);
}

TEST_F(InterpTest, SplitTracksMoveHighlightsWithTheView) {
  Scene scene = specularPlane();
  ShearingCamera cam(*scene.camera, 96, 72, 9);
  const test::CaptureSink reference = test::renderViews(*makeDeferredRenderer(scene, PixelType::U8), cam);
  InterpOptions options{.acquire = Acquire::Center};
  auto worst = [&](const test::CaptureSink& c) {
    double maxError = 0;
    for (const auto& [key, img] : reference.views)
      maxError = std::max(maxError, compareImages(img, c.views.at(key)).maxError);
    return maxError;
  };
  const double baked = worst(test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam));
  // K pairs of splits: the highlight is off by about 1/(K + 1) of its
  // peak (0.8) at most.
  options.splits = 3;
  RenderStats stats;
  const test::CaptureSink split = test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam, stats);
  EXPECT_GT(stats.counters["highlight_knots"], 2 * stats.counters["slices"]);
  EXPECT_GT(baked, 0.5);  // the baked highlight stays where the centre saw it
  EXPECT_LT(worst(split), 0.2);
  options.mode = PstMode::Cpu;
  EXPECT_GE(test::compareViews(split, test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam))
                .minPsnr, 40.0);
  // A diffuse scene has no highlight to split: the same images as K = 0.
  Scene diffuse = loadScene(test::assetPath("default.json"));
  ShearingCamera small(*diffuse.camera, 60, 45, 3);
  RenderStats none;
  const test::CaptureSink d3 = test::renderViews(
      *makeInterpRenderer(diffuse, PixelType::U8, {.acquire = Acquire::Center, .splits = 3}), small, none);
  const test::CaptureSink d0 =
      test::renderViews(*makeInterpRenderer(diffuse, PixelType::U8, {.acquire = Acquire::Center}), small);
  EXPECT_EQ(test::compareViews(d0, d3).minIdentical, 1.0);
  EXPECT_EQ(none.counters.count("highlight_knots"), 0u);
}

// Slicing runs in bands of scanlines on the pool; joined, every slot of
// the table holds the slice a single pass makes: the same ends, vector,
// texels and highlight knots (default scene beside a specular plane, split
// tracks and coalescing on, so every part of a slice is exercised).
TEST_F(InterpTest, SlicingInBandsJoinsToTheSingleBandTable) {
  Scene scene = specularPlane();
  const ShearingCamera cam(*scene.camera, 72, 45, 9);
  auto sources = makeSourceLayerRenderer(scene, true);
  RenderStats stats;
  const double track = cam.spec().trackRight - cam.spec().trackLeft;
  std::vector<SourceLayer> layers;
  for (double x : {cam.viewX(0), cam.viewX(8)})
    for (SourceLayer& l : sources->render(cam, {x, 0.0}, 4, track, stats)) layers.push_back(std::move(l));
  ImageSliceOptions options{.overlap = 0.25f, .coalesce = 0.5f, .scene = &scene, .splits = 2,
                            .bandRows = cam.height()};
  const ImageSlices whole = sliceSourceLayers(layers, cam, 0, options);
  ASSERT_GT(whole.vertices.knots.size(), 0u);
  for (int bandRows : {1, 7}) {
    options.bandRows = bandRows;
    const ImageSlices banded = sliceSourceLayers(layers, cam, 0, options);
    ASSERT_TRUE(std::ranges::equal(banded.table.offsets(), whole.table.offsets())) << bandRows;
    EXPECT_EQ(banded.pixels, whole.pixels);
    const auto& wv = whole.vertices;
    const auto& bv = banded.vertices;
    for (size_t s = 0; s < whole.table.sliceCount(); ++s) {
      const uint32_t a = whole.table.slices()[s].triangle, b = banded.table.slices()[s].triangle;
      for (int end = 0; end < 2; ++end) {
        const uint32_t p = wv.triangles[a][end], q = bv.triangles[b][end];
        ASSERT_EQ(wv.x0[p], bv.x0[q]) << bandRows << " slot " << s;
        ASSERT_EQ(wv.y[p], bv.y[q]);
        ASSERT_EQ(wv.depth[p], bv.depth[q]);
        ASSERT_EQ(wv.frontOverW[p], bv.frontOverW[q]);
      }
      const SliceVector &x = wv.vectors[a], &y = bv.vectors[b];
      ASSERT_EQ(x.length, y.length);
      ASSERT_EQ(x.u0, y.u0);
      ASSERT_EQ(x.knotCount, y.knotCount);
      for (int t = 0; t < 2 * x.length - 1; ++t)
        ASSERT_EQ(wv.vectorTexels.texels()[x.base + t], bv.vectorTexels.texels()[y.base + t]);
      for (int k = 0; k < x.knotCount; ++k) {
        ASSERT_EQ(wv.knots[x.firstKnot + k].r, bv.knots[y.firstKnot + k].r);
        ASSERT_EQ(wv.knots[x.firstKnot + k].specular, bv.knots[y.firstKnot + k].specular);
      }
    }
  }
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
  EXPECT_THROW(makeInterpRenderer(scene, PixelType::U8, {.coalesce = -1.0f}), Error);
  EXPECT_THROW(makeInterpRenderer(scene, PixelType::U8, {.budget = 1}), Error);
  EXPECT_THROW(makeInterpRenderer(scene, PixelType::U8, {.outlineSamples = 0}), Error);
  EXPECT_THROW(makeInterpRenderer(scene, PixelType::U8, {.outlineSamples = 17}), Error);
  EXPECT_THROW(makeInterpRenderer(scene, PixelType::U8, {.splits = -1}), Error);
}

}  // namespace
}  // namespace mvr
