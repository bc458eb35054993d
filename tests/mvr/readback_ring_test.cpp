// The readback ring, staged (pixel-pack buffers and fences) and direct:
// every batch lands in its own destination, batches complete in
// submission order, none before its reads are issued, all by drain().
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "mvr/error.h"
#include "mvr/gl/readback_ring.h"
#include "tests/support/gl_fixture.h"

namespace mvr {
namespace {

class ReadbackRingTest : public ::testing::TestWithParam<ReadbackStaging> {
 protected:
  void SetUp() override {
    test::sharedContext();
    setReadbackStaging(GetParam());
  }
  void TearDown() override { setReadbackStaging(ReadbackStaging::Auto); }
};

TEST_P(ReadbackRingTest, EveryBatchLandsInOrder) {
  const int w = 8, h = 6, batches = 7;
  RenderTarget target(w, h, PixelType::U8);
  ReadbackRing ring(size_t(w) * h * 4, 3);
  EXPECT_EQ(ring.staged(), GetParam() == ReadbackStaging::Always);
  std::vector<Image> images(batches, Image(w, h, PixelType::U8));
  std::vector<int> completed;
  for (int b = 0; b < batches; ++b) {
    // Batch b clears the target to grey level 10 b; the next clear must
    // not reach its pixels however late they are copied out.
    const float level = 10.0f * b / 255.0f, colour[4] = {level, level, level, 1.0f};
    gl::ClearNamedFramebufferfv(target.framebuffer(), GL_COLOR, 0, colour);
    ring.readRows(target, 0, h / 2, reinterpret_cast<std::byte*>(images[b].row(0)));
    ring.readRows(target, h / 2, h - h / 2, reinterpret_cast<std::byte*>(images[b].row(h / 2)));
    ring.submit([&completed, b] { completed.push_back(b); });
    ASSERT_LE(int(completed.size()), b + 1);
  }
  ring.drain();
  ASSERT_EQ(int(completed.size()), batches);
  for (int b = 0; b < batches; ++b) {
    EXPECT_EQ(completed[b], b);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) ASSERT_EQ(images[b].row(y)[4 * x], 10 * b) << b << " " << x << "," << y;
  }
}

TEST_P(ReadbackRingTest, ReadsOneLayerOfALayeredTarget) {
  const int w = 4, h = 3, layers = 5;
  RenderTarget target(w, h, PixelType::U8, layers);
  gl::Framebuffer fbo = gl::Framebuffer::create();
  for (int l = 0; l < layers; ++l) {
    gl::NamedFramebufferTextureLayer(fbo.id(), GL_COLOR_ATTACHMENT0, target.colorTexture(), 0, l);
    const float level = 40.0f * l / 255.0f, colour[4] = {level, 0, 0, 1};
    gl::ClearNamedFramebufferfv(fbo.id(), GL_COLOR, 0, colour);
  }
  ReadbackRing ring(size_t(w) * h * 4, 2);
  Image third(w, h, PixelType::U8);
  ring.readLayer(target, 3, reinterpret_cast<std::byte*>(third.row(0)));
  bool done = false;
  ring.submit([&done] { done = true; });
  ring.drain();
  ASSERT_TRUE(done);
  EXPECT_EQ(third.row(0)[0], 120);
  EXPECT_EQ(third.row(h - 1)[4 * (w - 1)], 120);
}

// A batch of stacked runs read at once, large enough (4.3 MB) that the
// staged copy goes to the pool in 1 MB pieces: every row lands in its run's
// image at its place. Each target row holds its own number.
TEST_P(ReadbackRingTest, RowRunsLandInTheirImagesInPieces) {
  const int w = 512, run = 700, runs = 3, h = run * runs;
  RenderTarget target(w, h, PixelType::U8);
  auto texel = [](int x, int y) { return std::array<uint8_t, 4>{uint8_t(y % 251), uint8_t(y / 251), uint8_t(x), 255}; };
  std::vector<uint8_t> pattern;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (uint8_t c : texel(x, y)) pattern.push_back(c);
  gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl::TextureSubImage2D(target.colorTexture(), 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pattern.data());
  ReadbackRing ring(size_t(w) * 4 * h, 2);
  std::vector<Image> images(runs, Image(w, run, PixelType::U8));
  std::vector<std::byte*> dsts;
  for (Image& image : images) dsts.push_back(reinterpret_cast<std::byte*>(image.row(0)));
  ring.readRowRuns(target, 0, run, dsts);
  bool done = false;
  ring.submit([&done] { done = true; });
  ring.drain();
  ASSERT_TRUE(done);
  for (int k = 0; k < runs; ++k)
    for (int y = 0; y < run; ++y)
      for (int x : {0, w - 1}) {
        const auto expected = texel(x, k * run + y);
        for (int c = 0; c < 4; ++c) ASSERT_EQ(images[k].row(y)[4 * x + c], expected[c]) << k << " " << y << " " << x;
      }
}

INSTANTIATE_TEST_SUITE_P(Staging, ReadbackRingTest,
                         ::testing::Values(ReadbackStaging::Always, ReadbackStaging::Never),
                         [](const auto& info) {
                           return info.param == ReadbackStaging::Always ? "Staged" : "Direct";
                         });

TEST(ReadbackRing, AReadPastTheSlotThrows) {
  test::sharedContext();
  setReadbackStaging(ReadbackStaging::Always);
  RenderTarget target(8, 8, PixelType::U8);
  ReadbackRing ring(8 * 4 * 4, 2);  // four rows
  Image img(8, 8, PixelType::U8);
  EXPECT_THROW(ring.readRows(target, 0, 8, reinterpret_cast<std::byte*>(img.row(0))), Error);
  setReadbackStaging(ReadbackStaging::Auto);
}

}  // namespace
}  // namespace mvr
