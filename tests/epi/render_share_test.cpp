// A render split into shares (rows; scanlines for EPI renderers, views for
// view renderers) gives every frame exactly once, byte for byte as the
// whole render does: what lets processes of a split job write one set.
#include <gtest/gtest.h>

#include "apps/cli/job_split.h"
#include "mvr/backends/backend.h"
#include "mvr/assets/scene_io.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

using Frames = std::map<std::pair<int, int>, Image>;

const Frames& framesOf(const Renderer& r, const test::CaptureSink& s) {
  return r.order() == FrameOrder::Epi ? s.epis : s.views;
}

// Splits the renderer's own axis (scanlines or views) into uneven parts,
// and the rows into two.
std::vector<RenderShare> shares(const ShearingCamera& cam, FrameOrder order) {
  const int n = order == FrameOrder::Epi ? cam.height() : cam.views();
  const std::vector<IndexRange> parts{{0, 1}, {1, n / 3}, {n / 3, n / 3}, {n / 3, n}};
  std::vector<RenderShare> out;
  for (IndexRange rows : {IndexRange{0, 1}, IndexRange{1, cam.rows()}})
    for (IndexRange part : parts) {
      RenderShare s = cam.share();
      s.rows = rows;
      (order == FrameOrder::Epi ? s.scanlines : s.views) = part;
      out.push_back(s);
    }
  return out;
}

class RenderShareTest : public ::testing::TestWithParam<const char*> {};

TEST_P(RenderShareTest, PartsJoinIntoTheWholeRender) {
  test::sharedContext();
  Scene scene = loadScene(test::assetPath("default.json"));
  const ShearingCamera cam(*scene.camera, 48, 37, 7, 2);
  auto renderer = makeRenderer(parseBackendSpec(GetParam()), scene, PixelType::U8);
  test::CaptureSink whole, joined;
  RenderStats stats;
  renderer->render(cam, whole, stats);
  const Frames& expected = framesOf(*renderer, whole);
  ASSERT_EQ(expected.size(), size_t(cam.rows()) * (renderer->order() == FrameOrder::Epi ? cam.height() : cam.views()));
  for (const RenderShare& share : shares(cam, renderer->order())) {
    test::CaptureSink part;
    renderer->render(cam.withShare(share), part, stats);
    const Frames& got = framesOf(*renderer, part);
    const IndexRange axis = renderer->order() == FrameOrder::Epi ? share.scanlines : share.views;
    EXPECT_EQ(got.size(), size_t(share.rows.size()) * axis.size()) << "share rows " << share.rows.begin;
    for (const auto& [key, image] : got) {
      EXPECT_TRUE(share.rows.contains(key.first) && axis.contains(key.second));
      EXPECT_TRUE(joined.views.emplace(key, image).second) << "frame given twice";
    }
  }
  ASSERT_EQ(joined.views.size(), expected.size());
  for (const auto& [key, image] : expected)
    EXPECT_EQ(joined.views.at(key).bytes, image.bytes) << "row " << key.first << " frame " << key.second;
}

INSTANTIATE_TEST_SUITE_P(EveryBackend, RenderShareTest,
                         ::testing::Values("mvr:cpu", "mvr:spans", "mvr:quad", "mvr:strip", "mvr:exact",
                                           "mvr:strip:gpu-psts", "interp:dual", "interp:dual:track",
                                           "interp:dual:track:gpu-psts", "interp:dual:spans", "interp:hierarchical:1", "svr",
                                           "svr-layered", "deferred", "warp:dual:gl", "warp:dual:cpu",
                                           "warp:hierarchical:cpu"),
                         test::specTestName);

TEST(RenderShare, OutsideTheSetIsAnError) {
  const ShearingCamera cam(CameraSpec{}, 16, 8, 4, 2);
  RenderShare share = cam.share();
  share.scanlines = {2, 9};
  EXPECT_THROW(cam.withShare(share), Error);
  share = cam.share();
  share.rows = {1, 0};
  EXPECT_THROW(cam.withShare(share), Error);
}

}  // namespace
}  // namespace mvr

namespace mvr::app {
namespace {

TEST(JobSplit, PartsCoverEveryItemOnceEvenWithMorePartsThanItems) {
  for (int parts : {1, 2, 3, 7, 12}) {
    const std::vector<IndexRange> split = splitByCost({5, 1, 1, 1, 9, 0, 2}, parts);
    ASSERT_EQ(split.size(), size_t(parts));
    int next = 0;
    for (IndexRange r : split) {
      EXPECT_EQ(r.begin, next);
      EXPECT_GE(r.size(), 0);
      next = r.end;
    }
    EXPECT_EQ(next, 7);
  }
  // Cost, not count: the costly item stands alone.
  const std::vector<IndexRange> two = splitByCost({1, 1, 1, 1, 10}, 2);
  EXPECT_EQ(two[0].end, 4);
}

TEST(JobSplit, WholeRowsFirstThenTheRowsLeftAsAGrid) {
  const CameraSpec spec;
  const JobSplit rows = splitJob(ShearingCamera(spec, 64, 48, 10, 4), FrameOrder::Epi, 2);
  EXPECT_EQ(rows.wholeRows, 2);
  EXPECT_EQ(rows.gridBegin(), 4);
  EXPECT_EQ(rows.shares[1].size(), 1u);
  EXPECT_EQ(rows.shares[1][0].rows.begin, 2);
  EXPECT_EQ(rows.shares[1][0].scanlines.size(), 48);
  EXPECT_DOUBLE_EQ(rows.imbalance, 1.0);
  const JobSplit bands = splitJob(ShearingCamera(spec, 64, 48, 10, 1), FrameOrder::Epi, 3);
  EXPECT_EQ(bands.wholeRows, 0);
  EXPECT_EQ(bands.rowGroups, 1);
  EXPECT_EQ(bands.parts, 3);
  EXPECT_EQ(bands.shares[2][0].scanlines.end, 48);
  EXPECT_EQ(bands.shares[1][0].scanlines.begin, bands.shares[0][0].scanlines.end);
  const JobSplit views = splitJob(ShearingCamera(spec, 64, 48, 10, 1), FrameOrder::View, 2);
  EXPECT_EQ(views.axis, "views");
  EXPECT_EQ(views.shares[1][0].views.begin, 5);
  // 4 rows over 3 ranks: a row each, then the last row in 3 bands.
  const JobSplit rest = splitJob(ShearingCamera(spec, 64, 48, 10, 4), FrameOrder::Epi, 3);
  EXPECT_EQ(rest.wholeRows, 1);
  ASSERT_EQ(rest.shares[2].size(), 2u);
  EXPECT_EQ(rest.shares[2][0].rows.begin, 2);
  EXPECT_EQ(rest.shares[2][1].rows.begin, 3);
  EXPECT_EQ(rest.shares[2][1].scanlines.end, 48);
  EXPECT_EQ(rest.parts, 3);
  EXPECT_NEAR(rest.imbalance, 1.0, 0.02);  // 48 equal scanlines in 3 bands
  // 100 rows over 64 ranks: a row each, then the 36 left as 4 groups of 9
  // rows by 16 bands (every rank 1 + 9 / 16 rows: balanced), not 36 ranks
  // with two rows (1.28).
  const JobSplit hologram = splitJob(ShearingCamera(spec, 1920, 1080, 1000, 100), FrameOrder::Epi, 64);
  EXPECT_EQ(hologram.wholeRows, 1);
  EXPECT_EQ(hologram.rowGroups, 4);
  EXPECT_EQ(hologram.parts, 16);
  EXPECT_NEAR(hologram.imbalance, 1.0, 0.01);
  // 100 rows over 512 ranks: groups of rows by bands.
  const JobSplit big = splitJob(ShearingCamera(spec, 1920, 1080, 1000, 100), FrameOrder::Epi, 512);
  EXPECT_EQ(big.wholeRows, 0);
  EXPECT_EQ(big.rowGroups * big.parts, 512);
  EXPECT_GT(big.parts, 1);
  EXPECT_EQ(big.shares[size_t(big.parts) + 1][0].rows.begin, big.shares[0][0].rows.end);
  EXPECT_EQ(big.shares[size_t(big.parts) + 1][0].scanlines.begin, big.shares[1][0].scanlines.begin);
}

TEST(JobSplit, ScanlineCostsCountEachSlicesSetupAndPixels) {
  // One triangle on the image plane (the same in every view) with corners
  // at pixels (4, 8), (20, 8), (4, 16): scanline centres 8.5 .. 15.5 cross
  // it, 16 (1 - (y - 8) / 8) pixels wide. A 32-pixel row costs 32, a slice
  // 64 more plus its width.
  Scene scene;
  const ShearingCamera cam(CameraSpec{}, 32, 32, 4);
  auto at = [&](double px, double py) {
    return glm::vec3(float((px / 32.0 - 0.5) * cam.planeWidth()), float((0.5 - py / 32.0) * cam.planeHeight()), 0.0f);
  };
  scene.positions = {at(4, 8), at(20, 8), at(4, 16)};
  scene.triangles = {{0, 1, 2}};
  const std::vector<double> costs = scanlineCosts(scene, cam, 0);
  ASSERT_EQ(costs.size(), 32u);
  for (int j = 0; j < 32; ++j) {
    const double width = 16.0 * (1.0 - (j + 0.5 - 8.0) / 8.0);
    EXPECT_NEAR(costs[size_t(j)], (j >= 8 && j < 16) ? 32.0 + 64.0 + width : 32.0, 1e-3) << j;
  }
}

}  // namespace
}  // namespace mvr::app
