// A render split into shares (rows; scanlines for EPI renderers, views for
// view renderers) gives every frame exactly once, byte for byte as the
// whole render does: what lets processes of a split job write one set.
#include <gtest/gtest.h>

#include "epi/backend.h"
#include "mvr/io/scene_io.h"
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
                         ::testing::Values("mvr:cpu", "mvr:quad", "mvr:strip", "mvr:exact",
                                           "mvr:strip:gpu-psts", "interp:dual", "svr", "svr-layered",
                                           "deferred", "warp:dual"),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return name;
                         });

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
