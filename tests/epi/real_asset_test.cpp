// Every back end on a scene of real-asset formats (tests/support/
// asset_scene.h: a glTF and an OBJ with its MTL, two texture sizes, a
// highlight, vertex colours, a node hierarchy), each against svr.
// Tolerances, min PSNR per view at 96 x 64, 9 views: MVR's modes and the
// baselines >= 35 dB (as on the bundled scenes); interp and warp, which
// fill views from a few rendered ones, >= 22 dB. (mvr:spans shades
// diffuse scenes only and says so.) With GPU-built PSTs, the texture
// vectors of the second texture came from the first until the prefix sum
// between the extraction's passes stopped taking the Materials block.
#include <gtest/gtest.h>

#include <filesystem>

#include "mvr/backends/backend.h"
#include "mvr/assets/scene_io.h"
#include "tests/support/asset_scene.h"
#include "tests/support/cli.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

class RealAssetTest : public ::testing::TestWithParam<const char*> {};

// Written into a folder of this process's own: ctest runs each case as a
// process, two at a time, and a shared folder was read while rewritten.
const Scene& assetScene() {
  static const Scene scene = loadScene(test::writeAssetScene(test::freshDir("real_asset")));
  return scene;
}

TEST_P(RealAssetTest, RendersCloseToSvr) {
  test::sharedContext();
  const Scene& scene = assetScene();
  const ShearingCamera cam(cameraFor(scene, 96, 64), 96, 64, 9);
  static const test::CaptureSink reference = test::renderSpec("svr", scene, cam);
  const std::string spec = GetParam();
  const test::CaptureSink views = test::renderSpec(spec, scene, cam);
  test::expectCloseToSvr(reference, views, spec, 35.0);
}

INSTANTIATE_TEST_SUITE_P(EveryBackend, RealAssetTest,
                         ::testing::Values("mvr:cpu", "mvr:quad", "mvr:strip", "mvr:exact", "mvr:exact:direct",
                                           "mvr:strip:gpu-psts", "mvr:exact:gpu-psts", "interp:dual",
                                           "interp:dual:spans", "svr-layered", "deferred", "warp:dual:gl",
                                           "warp:dual:cpu"),
                         test::specTestName);

}  // namespace
}  // namespace mvr
