// Cut-outs (glTF's alphaMode MASK, Material::alphaCutoff) in every back
// end: a red quad whose texture's left half has alpha 0 stands in front of
// a green one. Where the texture is cut, the green quad shows (the cut
// texels neither draw nor hide); elsewhere the red one does. Checked at a
// point well inside each half in the centre view (exact colours: 0.02),
// against svr per view (PSNR >= 40 dB at 96 x 64, 5 views: the cut edge
// falls where each path's texture filter puts alpha 0.5; interp and warp,
// which fill views from a few rendered ones, >= 22 dB), and in depth maps:
// the cut half has the green quad's depth.
#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>

#include "mvr/backends/backend.h"
#include "mvr/depth.h"
#include "mvr/images/image_file.h"
#include "mvr/assets/scene_io.h"
#include "tests/support/meshes.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

constexpr glm::vec3 kRed(0.9f, 0.1f, 0.1f), kGreen(0.2f, 0.8f, 0.2f);

void addQuad(Scene& s, float half, float z, uint32_t material) {
  test::addQuad(s, glm::vec3(-half, -half, z), glm::vec2(2.0f * half), material);
}

Scene cutOutScene() {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("mvr_cutout_test_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  Image half(8, 8, PixelType::Srgb8);
  for (int y = 0; y < 8; ++y)
    for (int x = 0; x < 8; ++x) half.setLinear(x, y, glm::vec4(1.0f, 1.0f, 1.0f, x < 4 ? 0.0f : 1.0f));
  Scene s;
  Material green, red;
  green.diffuse = kGreen;
  red.diffuse = kRed;
  red.texture = (dir / "left_cut.png").string();
  writeImage(half, red.texture);
  red.alphaCutoff = 0.5f;
  s.materials = {green, red};
  // Sizes that put no edge on a pixel centre: there fill rules decide, and
  // a whole silhouette column may differ from svr's (extremes_test.cpp).
  addQuad(s, 1.237f, -0.5f, 0);
  addQuad(s, 0.813f, 0.0f, 1);
  s.lights = {Light{Light::Type::Directional, glm::vec3(0, 0, -1), glm::vec3(1.0f)}};
  s.ambient = glm::vec3(0.0f);
  return s;
}

class CutOutTest : public ::testing::TestWithParam<const char*> {};

TEST_P(CutOutTest, CutTexelsNeitherDrawNorHide) {
  test::sharedContext();
  static const Scene scene = cutOutScene();
  const ShearingCamera cam(cameraFor(scene, 96, 64), 96, 64, 5);
  static const test::CaptureSink reference = test::renderSpec("svr", scene, cam);
  const std::string spec = GetParam();
  const test::CaptureSink views = test::renderSpec(spec, scene, cam);
  for (const test::CaptureSink* set : {&reference, &views}) {
    const Image& centre = set->views.at({0, 2});
    auto colourAt = [&](float x) {
      const glm::vec3 at = cam.project(glm::dvec3(x, 0.0, 0.0), 2);
      return glm::vec3(centre.linear(int(at.x), int(at.y)));
    };
    EXPECT_NEAR(glm::distance(colourAt(-0.4f), kGreen), 0.0f, 0.02f) << spec << (set == &reference ? " (svr)" : "");
    EXPECT_NEAR(glm::distance(colourAt(0.4f), kRed), 0.0f, 0.02f) << spec << (set == &reference ? " (svr)" : "");
  }
  test::expectCloseToSvr(reference, views, spec, 40.0);
}

INSTANTIATE_TEST_SUITE_P(EveryBackend, CutOutTest,
                         ::testing::Values("mvr:cpu", "mvr:quad", "mvr:strip", "mvr:exact", "mvr:exact:direct",
                                           "mvr:strip:gpu-psts", "mvr:exact:gpu-psts", "interp:dual",
                                           "svr-layered", "deferred", "warp:dual:gl", "warp:dual:cpu"),
                         test::specTestName);

// The depth scene keeps a cut-out's alpha (and only that): depth maps see
// through the cut half to the green quad, 0.5 further than the red one
// (both face the camera, so every pixel of each has one depth).
TEST(CutOut, DepthMapsSeeThroughTheCut) {
  test::sharedContext();
  const Scene scene = cutOutScene();
  const ShearingCamera cam(cameraFor(scene, 96, 64), 96, 64, 3);
  for (const char* spec : {"svr", "mvr:cpu", "mvr:exact"}) {
    DepthColoring coloring;
    const Scene depth = depthScene(scene, cam, coloring);
    auto renderer = makeRenderer(parseBackendSpec(spec), depth, PixelType::F32);
    const test::CaptureSink views = test::renderViews(*renderer, cam, PixelType::F32);
    const DepthImage d = depthFromColors(views.views.at({0, 1}), coloring);
    auto depthAt = [&](float x) {
      const glm::vec3 at = cam.project(glm::dvec3(x, 0.0, 0.0), 1);
      return d.at(int(at.x), int(at.y));
    };
    const float front = depthAt(0.4f), behind = depthAt(-0.4f);
    EXPECT_NEAR(behind - front, 0.5f, 1e-3f) << spec;
  }
}

}  // namespace
}  // namespace mvr
