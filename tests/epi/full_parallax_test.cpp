// Full parallax (Halle 5.6.11): rows of views differ only in y, by a
// per-vertex step; MVR grids agree with SVR grids view by view.
#include <gtest/gtest.h>

#include "mvr/assets/scene_io.h"
#include "slicing/extreme_vertices.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

TEST(FullParallax, RowStepEqualsTransformingEachRow) {
  Scene scene = loadScene(test::assetPath("default.json"));
  ShearingCamera cam(*scene.camera, 80, 60, 5, 4);
  auto colors = shading::litVertexColors(scene);
  ExtremeVertices stepped = transformToExtremes(scene, colors, cam, 0);
  for (int row = 1; row < 4; ++row) {
    moveToRow(stepped, row);
    ExtremeVertices direct = transformToExtremes(scene, colors, cam, row);
    ASSERT_EQ(direct.y.size(), stepped.y.size());
    for (size_t i = 0; i < direct.y.size(); ++i) ASSERT_NEAR(stepped.y[i], direct.y[i], 2e-4) << i;
    EXPECT_EQ(direct.x0, stepped.x0);  // x does not depend on the row
  }
}

TEST(FullParallax, GridMatchesSvrGrid) {
  test::sharedContext();
  Scene scene = loadScene(test::assetPath("default.json"));
  ShearingCamera cam(*scene.camera, 64, 48, 4, 3);
  auto svr = makeSvrRenderer(scene, PixelType::U8);
  auto mvr = makeMvrRenderer(scene, PstMode::Cpu, PixelType::U8);
  test::CaptureSink a = test::renderViews(*svr, cam), b = test::renderViews(*mvr, cam);
  ASSERT_EQ(a.views.size(), 12u);
  test::expectCloseOnAnyGl(test::compareViews(a, b), 0.99, 40.0, "cpu");
  // Rows really differ: the top and bottom rows see the cup from above and below.
  EXPECT_LT(compareImages(a.views.at({0, 1}), a.views.at({2, 1})).identicalFraction, 0.95);
}

}  // namespace
}  // namespace mvr
