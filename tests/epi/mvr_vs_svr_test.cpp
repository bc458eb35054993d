// MVR against SVR on the same scene and camera, per view. Tolerances:
//  cpu, exact  >= 99.5% of pixels within one 8-bit step and PSNR >= 40 dB
//              (test::expectCloseOnAnyGl has the derivation); what differs
//              more is silhouette pixels where the two rasterizers' fill
//              rules and sub-pixel snapping disagree. (At 96 x 72 one
//              full-contrast silhouette pixel alone costs 42 dB, so 45 dB
//              would demand pixel-identical silhouettes.)
//  strip       PSNR >= 40 dB: slivers interpolate linearly between exact
//              rulings, half a pixel of attribute misplacement at most.
//  quad        on a strongly twisted scene, measurably worse than strip.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "mvr/gl/readback_ring.h"
#include "mvr/assets/scene_io.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

class MvrVsSvr : public test::GlTest {
 protected:
  test::SetDifference run(const Scene& scene, const ShearingCamera& cam, PstMode mode) {
    auto svr = makeSvrRenderer(scene, PixelType::U8);
    auto mvr = makeMvrRenderer(scene, mode, PixelType::U8);
    return test::compareViews(test::renderViews(*svr, cam), test::renderViews(*mvr, cam));
  }
};

TEST_F(MvrVsSvr, CubeExactModesMatch) {
  Scene scene = loadScene(test::assetPath("cube.json"));
  ShearingCamera cam(*scene.camera, 96, 72, 9);
  for (PstMode mode : {PstMode::Cpu, PstMode::Exact})
    test::expectCloseOnAnyGl(run(scene, cam, mode), 0.995, 40.0, pstModeName(mode));
}

TEST_F(MvrVsSvr, TeacupExactModesMatchAndStripIsClose) {
  Scene scene = loadScene(test::assetPath("default.json"));
  ShearingCamera cam(*scene.camera, 120, 90, 7);
  for (PstMode mode : {PstMode::Cpu, PstMode::Exact})
    test::expectCloseOnAnyGl(run(scene, cam, mode), 0.995, 40.0, pstModeName(mode));
  auto strip = run(scene, cam, PstMode::Strip);
  EXPECT_GE(strip.minPsnr, 40.0);
}

// A quad running steeply in depth, coloured red (near) to green (far): its
// slices twist strongly across a wide track.
Scene twistedScene() {
  Scene s;
  s.positions = {{-1.2f, -0.8f, 1.8f}, {1.2f, -0.8f, -3.0f}, {1.2f, 0.8f, -3.0f}, {-1.2f, 0.8f, 1.8f}};
  s.normals.assign(4, glm::vec3(0, 0, 1));
  s.colors = {{1, 0, 0}, {0, 1, 0.2f}, {0, 0.2f, 1}, {1, 1, 0}};
  s.triangles = {{0, 1, 2}, {0, 2, 3}};
  s.materialIds = {0, 0};
  Material m;
  m.diffuse = glm::vec3(1);
  s.materials = {m};
  s.ambient = glm::vec3(1);  // unlit: colours exactly as given
  return s;
}

TEST_F(MvrVsSvr, QuadIsMeasurablyWorseOnATwistedScene) {
  Scene scene = twistedScene();
  CameraSpec spec;
  spec.distance = 4;
  spec.planeWidth = 3;
  spec.trackLeft = -3;
  spec.trackRight = 3;
  spec.nearDistance = 1;
  spec.farDistance = 9;
  ShearingCamera cam(spec, 96, 64, 16);
  auto quad = run(scene, cam, PstMode::Quad);
  auto strip = run(scene, cam, PstMode::Strip);
  auto exact = run(scene, cam, PstMode::Exact);
  EXPECT_GE(exact.minPsnr, 40.0);
  EXPECT_GE(strip.minPsnr, 35.0);
  EXPECT_LT(quad.minPsnr, strip.minPsnr - 3.0) << "quad " << quad.minPsnr << " strip " << strip.minPsnr;
}

// PST geometry built on the GPU (vertex pulling from the GPU slice table)
// against the same geometry built on the CPU. Both describe the same
// triangles; their vertices differ only by float rounding (the shader may
// contract a multiply-add the CPU rounds twice), a few 1e-5 px at these
// widths. A pixel changes only where its centre lies that close to an
// edge, or where a colour sits on an 8-bit rounding boundary: at most a
// few pixels in 10^4, and never by more than one step away from edges.
// Scenes: the teacup (culling, many thin slices), the twisted quad (strip
// with many slivers), the shiny scene (specular pass: depth EQUAL across
// passes needs the same depths in every pass), the mirror (reflection)
// and the textured scene, sampled directly and by texture vectors (the
// GPU extracts them with the GL's sampler, the CPU with TextureSet's: the
// same trilinear filter, the GL's weights rounded to its sub-texel
// precision, llvmpipe: 83% of pixels identical, 59.9 dB; the vectors'
// lengths must agree, so their texel counts do).
TEST_F(MvrVsSvr, GpuBuiltPstsMatchCpuBuiltPsts) {
  struct Case {
    std::string name;
    Scene scene;
    ShearingCamera cam;
    TextureMode texture = TextureMode::Direct;
  };
  Scene twisted = twistedScene();
  CameraSpec spec;
  spec.distance = 4, spec.planeWidth = 3, spec.trackLeft = -3, spec.trackRight = 3;
  spec.nearDistance = 1, spec.farDistance = 9;
  std::vector<Case> cases;
  for (const char* name : {"default.json", "shiny.json", "mirror.json", "textured.json"}) {
    Scene s = loadScene(test::assetPath(name));
    const ShearingCamera cam(*s.camera, 96, 72, 9);
    cases.push_back({name, std::move(s), cam});
  }
  cases.push_back({"twisted", twisted, ShearingCamera(spec, 96, 64, 16)});
  cases.push_back({"textured.json vectors", cases[3].scene, cases[3].cam, TextureMode::Vector});
  for (const Case& c : cases) {
    for (PstMode mode : {PstMode::Quad, PstMode::Strip, PstMode::Exact}) {
      auto gpu = makeMvrRenderer(c.scene, mode, PixelType::U8, c.texture, PstBuilder::Gpu);
      auto cpu = makeMvrRenderer(c.scene, mode, PixelType::U8, c.texture, PstBuilder::Cpu);
      RenderStats gpuStats, cpuStats;
      const auto gpuViews = test::renderViews(*gpu, c.cam, gpuStats);
      const auto cpuViews = test::renderViews(*cpu, c.cam, cpuStats);
      EXPECT_EQ(gpuStats.notes["pst_builder"], "gpu");
      EXPECT_EQ(cpuStats.notes["pst_builder"], "cpu");
      const std::string label = std::string(pstModeName(mode)) + " " + c.name;
      EXPECT_EQ(gpuStats.counters["texture_vector_texels"], cpuStats.counters["texture_vector_texels"])
          << label;
      if (c.texture == TextureMode::Vector) {
        EXPECT_GT(gpuStats.counters["texture_vector_texels"], 0) << label;
      }
      const auto d = test::compareViews(cpuViews, gpuViews);
      if (c.texture == TextureMode::Vector) {  // texels filtered by two samplers
        test::expectCloseOnAnyGl(d, 0.9995, 45.0, label);
        continue;
      }
      EXPECT_GE(d.minIdentical, 0.999) << label;
      EXPECT_GE(d.minClose, 0.9995) << label;
      EXPECT_GE(d.minPsnr, 45.0) << label;
    }
  }
}

// Every texturing builds its PSTs where the option says (the texture
// vectors too: extracted on the GPU); auto builds on the GPU unless GL
// renders on the CPU.
TEST_F(MvrVsSvr, PstBuilderFollowsTheOption) {
  Scene scene = loadScene(test::assetPath("textured.json"));
  ShearingCamera cam(*scene.camera, 48, 36, 4);
  for (TextureMode texture : {TextureMode::Vector, TextureMode::Direct}) {
    for (PstBuilder builder : {PstBuilder::Gpu, PstBuilder::Cpu, PstBuilder::Auto}) {
      auto mvr = makeMvrRenderer(scene, PstMode::Strip, PixelType::U8, texture, builder);
      RenderStats stats;
      test::renderViews(*mvr, cam, stats);
      const bool gpu = builder == PstBuilder::Gpu || (builder == PstBuilder::Auto && !gl::rendersOnCpu());
      EXPECT_EQ(stats.notes["pst_builder"], gpu ? "gpu" : "cpu");
    }
  }
}

// Reads staged through the readback ring's pixel-pack buffers and fences
// (the GPU path) give exactly the images of direct reads (llvmpipe's
// path), for every view-major baseline and MVR, across several batches
// and more frames than the ring has slots.
TEST_F(MvrVsSvr, StagedReadbackChangesNoPixel) {
  Scene scene = loadScene(test::assetPath("shiny.json"));
  ShearingCamera cam(*scene.camera, 64, 48, 7);
  using Factory = std::unique_ptr<Renderer> (*)(const Scene&, PixelType);
  const std::pair<const char*, Factory> backEnds[] = {
      {"svr", makeSvrRenderer},
      {"svr-layered", [](const Scene& s, PixelType t) { return makeLayeredSvrRenderer(s, t, true); }},
      {"deferred", makeDeferredRenderer},
      {"mvr", [](const Scene& s, PixelType t) { return makeMvrRenderer(s, PstMode::Exact, t); }}};
  for (const auto& [name, make] : backEnds) {
    test::CaptureSink images[2];
    for (int staged = 0; staged < 2; ++staged) {
      setReadbackStaging(staged ? ReadbackStaging::Always : ReadbackStaging::Never);
      auto renderer = make(scene, PixelType::U8);
      images[staged] = test::renderViews(*renderer, cam);
    }
    setReadbackStaging(ReadbackStaging::Auto);
    const auto d = test::compareViews(images[0], images[1]);
    EXPECT_EQ(d.minIdentical, 1.0) << name;
    EXPECT_EQ(images[1].views.size(), 7u) << name;
  }
  // Thousands of views: a handful of scanlines per batch (a batch's EPIs
  // are stacked up to GL_MAX_TEXTURE_SIZE rows: 16384 on llvmpipe, 32768 on
  // NVIDIA), so MVR's batches wrap around the three-slot ring.
  ShearingCamera many(*scene.camera, 32, 24, 6000);
  test::CaptureSink epis[2];
  for (int staged = 0; staged < 2; ++staged) {
    setReadbackStaging(staged ? ReadbackStaging::Always : ReadbackStaging::Never);
    auto mvr = makeMvrRenderer(scene, PstMode::Strip, PixelType::U8);
    RenderStats stats;
    mvr->render(many, epis[staged], stats);
    const int batch = int(stats.counters["epis_per_draw"]);
    EXPECT_GE((24 + batch - 1) / batch, 4) << batch << " EPIs per draw";
  }
  setReadbackStaging(ReadbackStaging::Auto);
  ASSERT_EQ(epis[1].epis.size(), 24u);
  for (const auto& [key, epi] : epis[0].epis) EXPECT_EQ(epi.bytes, epis[1].epis.at(key).bytes);
}

// svr-layered draws layers where they pay (a GPU) and single views where
// the GL rasterises on the CPU; forced layers always layer.
TEST_F(MvrVsSvr, LayeredSvrLayersOnlyWhereLayersPay) {
  Scene scene = loadScene(test::assetPath("cube.json"));
  ShearingCamera cam(*scene.camera, 32, 24, 5);
  for (bool force : {false, true}) {
    auto layered = makeLayeredSvrRenderer(scene, PixelType::U8, force);
    RenderStats stats;
    test::renderViews(*layered, cam, stats);
    const bool perView = gl::rendersOnCpu() && !force;
    EXPECT_EQ(stats.notes["layer_routing"].rfind("none", 0) == 0, perView) << stats.notes["layer_routing"];
    EXPECT_EQ(stats.counters.count("layers_per_draw") == 1, !perView);
  }
}

TEST_F(MvrVsSvr, OneAndTwoViews) {
  Scene scene = loadScene(test::assetPath("cube.json"));
  for (int n : {1, 2}) {
    ShearingCamera cam(*scene.camera, 64, 48, n);
    test::expectCloseOnAnyGl(run(scene, cam, PstMode::Cpu), 0.995, 40.0, std::to_string(n) + " views");
  }
}

TEST_F(MvrVsSvr, EpiOrderReorderedEqualsViews) {
  Scene scene = loadScene(test::assetPath("cube.json"));
  ShearingCamera cam(*scene.camera, 40, 30, 5);
  auto mvr = makeMvrRenderer(scene, PstMode::Exact, PixelType::U8);
  test::CaptureSink epis;
  RenderStats stats;
  mvr->render(cam, epis, stats);
  ASSERT_EQ(epis.epis.size(), 30u);
  test::CaptureSink views = test::renderViews(*mvr, cam);
  for (int i = 0; i < 5; ++i)
    for (int j = 0; j < 30; ++j)
      ASSERT_EQ(0, std::memcmp(views.views.at({0, i}).row(j), epis.epis.at({0, j}).row(i), 40 * 4))
          << "view " << i << " scanline " << j;
  EXPECT_GT(stats.counters["slices"], 0);
  EXPECT_TRUE(stats.times.seconds.count("slicing"));
}

}  // namespace
}  // namespace mvr
