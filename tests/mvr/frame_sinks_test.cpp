#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "mvr/error.h"
#include "mvr/frames/frame_sinks.h"
#include "mvr/frames/progress.h"
#include "tests/support/capture_sink.h"

namespace mvr {
namespace {

// A view whose every pixel's red channel is its view number.
Image tagged(int w, int h, int tag) {
  Image img(w, h, PixelType::U8);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* p = img.row(y) + x * 4;
      p[0] = uint8_t(tag), p[1] = uint8_t(x), p[2] = uint8_t(y), p[3] = 255;
    }
  return img;
}

TEST(QuiltSink, ViewZeroIsBottomLeftAndViewsFillUpwards) {
  QuiltSink q(4, 3, 6, 1, PixelType::U8, 3, 2);
  for (int v = 0; v < 6; ++v) q.putView(0, v, tagged(4, 3, v));
  const Image& img = q.quilt();
  ASSERT_EQ(img.width, 12);
  ASSERT_EQ(img.height, 6);
  auto tagAt = [&](int tx, int ty) { return img.row(ty * 3 + 1)[(tx * 4 + 1) * 4]; };
  EXPECT_EQ(tagAt(0, 1), 0);  // bottom-left
  EXPECT_EQ(tagAt(2, 1), 2);  // bottom-right
  EXPECT_EQ(tagAt(0, 0), 3);  // top-left
  EXPECT_EQ(tagAt(2, 0), 5);
  EXPECT_EQ(q.fileName("png"), "quilt_qs3x2a1.33.png");
}

TEST(QuiltSink, TooFewTilesIsAnError) {
  EXPECT_THROW(QuiltSink(4, 3, 7, 1, PixelType::U8, 3, 2), Error);
}

TEST(PredistortSink, IdentityTableChangesNothingAndShiftMoves) {
  test::CaptureSink out;
  std::vector<float> identity = {0.5f, 1.5f, 2.5f, 3.5f};
  PredistortSink same(out, identity);
  Image img = tagged(4, 2, 9);
  same.putView(0, 0, img);
  EXPECT_EQ(out.views.at({0, 0}).bytes, img.bytes);
  PredistortSink shift(out, {1.5f, 2.5f, 3.5f, 4.5f});  // each column takes its right neighbour
  shift.putEpi(0, 0, img);
  const Image& s = out.epis.at({0, 0});
  EXPECT_EQ(s.row(0)[0 * 4 + 1], 1);
  EXPECT_EQ(s.row(0)[2 * 4 + 1], 3);
  EXPECT_EQ(s.row(0)[3 * 4 + 3], 0);  // beyond the image: transparent
}

TEST(PredistortSink, TableFilesAreValidated) {
  const auto dir = std::filesystem::temp_directory_path();
  const std::string good = (dir / "mvr_lut_good.txt").string(), bad = (dir / "mvr_lut_bad.txt").string();
  std::ofstream(good) << "0.5, 1.5\n2.5 3.5\n";
  std::ofstream(bad) << "0.5 x 2.5\n";
  EXPECT_EQ(loadPredistortionTable(good, 4).size(), 4u);
  EXPECT_THROW(loadPredistortionTable(good, 5), Error);
  EXPECT_THROW(loadPredistortionTable(bad, 3), Error);
  EXPECT_THROW(loadPredistortionTable((dir / "absent_lut.txt").string(), 3), Error);
}

// Progress in the user's unit: a share of the views, the rate, the time left.
TEST(Progress, LineCountsViewsWithRateAndTimeLeft) {
  EXPECT_EQ(progressLine("svr", 0.25, 100, 2.0), "mvr: 25% of 100 views (svr), 12.5 views/s, 6.0 s left");
  EXPECT_EQ(progressLine("mvr strip", 1.0, 8, 4.0), "mvr: 100% of 8 views (mvr strip), 2.0 views/s, 0.0 s left");
}

TEST(ProgressSink, HandsEveryFrameOn) {
  test::CaptureSink capture;
  const ShearingCamera cam(CameraSpec{}, 4, 3, 2);
  ProgressSink sink(capture, cam, 2, "test");
  sink.putEpi(0, 1, tagged(4, 2, 1));
  sink.putView(0, 0, tagged(4, 3, 0));
  sink.finish();
  EXPECT_EQ(capture.epis.count({0, 1}), 1u);
  EXPECT_EQ(capture.views.count({0, 0}), 1u);
}

}  // namespace
}  // namespace mvr
