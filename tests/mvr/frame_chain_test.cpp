// The frame chain (mvr/frames/frame_chain.h): which stages a description
// builds, in which order, and what it reports of its reorder.
#include <gtest/gtest.h>

#include "mvr/frames/frame_chain.h"
#include "tests/support/capture_sink.h"

namespace mvr {
namespace {

// EPI j of a 2-pixel, 3-view row: pixel (x, view i) holds 10 j + i in red,
// alpha 0 (a background shows through) and x in green.
Image epiOf(int j) {
  Image epi(2, 3, PixelType::U8);
  for (int i = 0; i < 3; ++i)
    for (int x = 0; x < 2; ++x) {
      uint8_t* p = epi.row(i) + x * 4;
      p[0] = uint8_t(10 * j + i), p[1] = uint8_t(x), p[2] = 0, p[3] = 0;
    }
  return epi;
}

FrameChainSpec episToViews() {
  return {.rendered = FrameOrder::Epi, .delivered = FrameOrder::View, .width = 2, .height = 4, .views = 3,
          .type = PixelType::U8};
}

TEST(FrameChain, SameOrderIsTheDestinationItself) {
  test::CaptureSink out;
  FrameChain chain({.sink = &out}, {.rendered = FrameOrder::View, .delivered = FrameOrder::View});
  EXPECT_EQ(&chain.entry(), &out);
  EXPECT_TRUE(chain.reorderInfo().is_null());
  EXPECT_EQ(chain.scratchNote(), "");
}

TEST(FrameChain, EpisBecomeViewsAndTheReorderIsReported) {
  test::CaptureSink out;
  FrameChain chain({.sink = &out}, episToViews());
  for (int j = 0; j < 4; ++j) chain.entry().putEpi(0, j, epiOf(j));
  chain.entry().finish();
  ASSERT_EQ(out.views.size(), 3u);
  EXPECT_TRUE(out.epis.empty());
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) EXPECT_EQ(out.views[std::pair(0, i)].row(j)[4], 10 * j + i);  // x = 1, red
  const nlohmann::json info = chain.reorderInfo();
  EXPECT_EQ(info["method"], "volume in memory");
  EXPECT_EQ(info["scratch_file"], false);
  EXPECT_EQ(info["frames_per_pass"], 3);
}

TEST(FrameChain, ViewsBecomeEpis) {
  test::CaptureSink views, out;
  {
    FrameChain toViews({.sink = &views}, episToViews());
    for (int j = 0; j < 4; ++j) toViews.entry().putEpi(0, j, epiOf(j));
  }
  FrameChain chain({.sink = &out}, {.rendered = FrameOrder::View, .delivered = FrameOrder::Epi, .width = 2,
                                    .height = 4, .views = 3, .type = PixelType::U8});
  for (int i = 0; i < 3; ++i) chain.entry().putView(0, i, views.views[std::pair(0, i)]);
  ASSERT_EQ(out.epis.size(), 4u);
  for (int j = 0; j < 4; ++j) EXPECT_EQ(out.epis[std::pair(0, j)].bytes, epiOf(j).bytes);
}

// The background is composited before the reorder: every pixel of every
// view, whatever order the frames came in.
TEST(FrameChain, BackgroundReachesEveryReorderedPixel) {
  test::CaptureSink out;
  FrameChainSpec spec = episToViews();
  spec.background = glm::vec4(0.0f, 0.0f, 1.0f, 1.0f);
  FrameChain chain({.sink = &out}, spec);
  for (int j = 0; j < 4; ++j) chain.entry().putEpi(0, j, epiOf(j));
  ASSERT_EQ(out.views.size(), 3u);
  for (const auto& [key, view] : out.views)
    for (int y = 0; y < 4; ++y)
      for (int x = 0; x < 2; ++x) {
        EXPECT_EQ(view.row(y)[x * 4 + 2], 255) << "view " << key.second;  // blue shows through alpha 0
        EXPECT_EQ(view.row(y)[x * 4 + 3], 255);
      }
}

// A quilt beside the frames, or the quilt alone.
TEST(FrameChain, QuiltTeeAndQuiltOnly) {
  for (bool frames : {true, false}) {
    test::CaptureSink out;
    QuiltSink quilt(2, 4, 3, 1, PixelType::U8, 3, 1);
    FrameChain chain({.sink = &out, .quilt = &quilt, .frames = frames}, episToViews());
    for (int j = 0; j < 4; ++j) chain.entry().putEpi(0, j, epiOf(j));
    EXPECT_EQ(out.views.size(), frames ? 3u : 0u);
    EXPECT_EQ(quilt.quilt().row(0)[(2 * 2 + 1) * 4], 10 * 0 + 2);  // view 2's scanline 0, x = 1
  }
}

// Supersampling is the outermost stage: the renderer hands it samples.
TEST(FrameChain, SupersamplingTakesTheSamples) {
  test::CaptureSink out;
  FrameChain chain({.sink = &out}, {.rendered = FrameOrder::View, .delivered = FrameOrder::View, .width = 1,
                                    .height = 1, .views = 1, .type = PixelType::F32,
                                    .aa = Supersampling{.spatial = 2}});
  Image samples(2, 2, PixelType::F32);
  float* p = reinterpret_cast<float*>(samples.bytes.data());
  for (int k = 0; k < 4; ++k) p[k * 4] = float(k), p[k * 4 + 3] = 1.0f;
  chain.entry().putView(0, 0, samples);
  chain.entry().finish();
  ASSERT_EQ(out.views.size(), 1u);
  const Image& view = out.views[std::pair(0, 0)];
  ASSERT_EQ(view.width, 1);
  EXPECT_FLOAT_EQ(reinterpret_cast<const float*>(view.bytes.data())[0], 1.5f);  // the mean of 0..3
}

}  // namespace
}  // namespace mvr
