// Our depth EXR encoder (mvr/images/exr_depth.h) read back through OpenImageIO
// (OpenEXR's own reader): the same floats, bit for bit, as the maps it was
// given and as OpenImageIO's encoder wrote; the codec the file says; ZIP
// chunks that shrink where depth is flat and stay raw where noise does not
// deflate.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>

#include "mvr/error.h"
#include "mvr/files/atomic_file.h"
#include "mvr/images/exr_depth.h"
#include "mvr/images/image_codec.h"
#include "mvr/images/image_file.h"
#include "tests/support/cli.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;

// Background (0), a slope, steps, noise in the mantissa, and the extremes
// of a float.
DepthImage depthPattern(int w, int h) {
  DepthImage d(w, h);
  uint32_t seed = 99;
  const float extremes[] = {std::numeric_limits<float>::min(), std::numeric_limits<float>::max(),
                            std::numeric_limits<float>::denorm_min(), 1e-30f, 3.5f};
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      seed = seed * 1664525u + 1013904223u;
      float v = 0.0f;
      if (x % 7 == 0 && y % 3 == 0) v = extremes[(x + y) % 5];
      else if (x > w / 4 && x < w / 2) v = 2.0f + 0.01f * float(x) + 0.003f * float(y);
      else if (x >= w / 2) v = float(1 + (x / 5) % 4) + float(seed >> 8) * 1e-9f;
      d.at(x, y) = v;
    }
  return d;
}

bool sameBits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// Sizes: one pixel; a last chunk of 7 of 16 scanlines; rows past deflate's
// window (17000 wide: 34000 bytes a row in each half), in both codecs.
TEST(ExrDepth, OpenExrReadsBackEveryFloat) {
  const fs::path dir = test::freshDir("exr_depth");
  fs::create_directories(dir);
  for (const glm::ivec2 size : {glm::ivec2(1, 1), glm::ivec2(37, 23), glm::ivec2(640, 48), glm::ivec2(17000, 3)})
    for (const char* codec : {"zip", "none"}) {
      const std::string what = std::to_string(size.x) + "x" + std::to_string(size.y) + " " + codec;
      const DepthImage depth = depthPattern(size.x, size.y);
      const std::string ours = (dir / "ours.exr").string(), theirs = (dir / "theirs.exr").string();
      writeDepthImage(depth, ours, {.codec = codec});
      std::vector<unsigned char> bytes;
      ASSERT_EQ(imageCodec().encodeDepth(depth, {.codec = codec}, bytes), "") << what;
      writeFileAtomically(theirs, std::as_bytes(std::span(bytes)));
      const DepthImage back = readDepthImage(ours);
      ASSERT_EQ(back.width, size.x) << what;
      ASSERT_EQ(back.height, size.y) << what;
      EXPECT_TRUE(sameBits(back.values, depth.values)) << what;
      EXPECT_TRUE(sameBits(back.values, readDepthImage(theirs).values)) << what;
      EXPECT_EQ(readImageEncoding(ours).codec, codec) << what;
      EXPECT_EQ(readImageEncoding(ours).bits, 32) << what;
    }
}

// Flat depth deflates to under 4% (each chunk has its own Huffman codes);
// noise in every bit is stored raw (no bigger than the floats and the
// chunk tables).
TEST(ExrDepth, ZipChunksShrinkFlatDepthAndKeepNoiseRaw) {
  DepthImage flat(256, 64), noise(256, 64);
  for (float& v : flat.values) v = 4.25f;
  uint32_t seed = 5;
  for (float& v : noise.values) {
    seed = seed * 1664525u + 1013904223u;
    uint32_t bits = seed;
    std::memcpy(&v, &bits, 4);
    if (!std::isfinite(v)) v = 1.0f;
  }
  std::vector<unsigned char> a, b;
  encodeDepthExr(flat, true, a);
  encodeDepthExr(noise, true, b);
  const size_t raw = 256 * 64 * 4;
  EXPECT_LT(a.size(), raw / 25);
  EXPECT_LE(b.size(), raw + 1024);
  EXPECT_GT(b.size(), raw);
}

TEST(ExrDepth, AnEmptyMapIsAnError) {
  std::vector<unsigned char> out;
  EXPECT_THROW(encodeDepthExr(DepthImage(), true, out), Error);
}

}  // namespace
}  // namespace mvr
