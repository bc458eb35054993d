// The image pool: images come back once their last user lets go and are
// handed out again for the same shape only; one may outlive the pool.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <set>

#include "mvr/image_pool.h"

namespace mvr {
namespace {

// A frame-sized image's pixels start on a 2 MiB boundary (where a huge
// page can hold them), zeroed; a small one's are ordinary memory. Both
// copy, grow and free as a vector's.
TEST(ImagePool, FrameSizedPixelsStartOnAHugePage) {
  const Image quilt(1200, 1000, PixelType::Srgb8);  // 4.8 MB
  EXPECT_EQ(reinterpret_cast<uintptr_t>(quilt.bytes.data()) % (uintptr_t(2) << 20), 0u);
  EXPECT_TRUE(std::all_of(quilt.bytes.begin(), quilt.bytes.end(), [](uint8_t b) { return b == 0; }));
  Image copy = quilt;
  copy.bytes.back() = 7;
  EXPECT_EQ(quilt.bytes.back(), 0);
  Image small(4, 4, PixelType::U8);
  small.bytes.resize(size_t(8) << 20, 1);  // grows past the threshold
  EXPECT_EQ(small.bytes[(size_t(8) << 20) - 1], 1);
  EXPECT_EQ(small.bytes[0], 0);
}

TEST(ImagePool, AnImageLetGoIsHandedOutAgainForItsShapeOnly) {
  ImagePool pool;
  std::shared_ptr<Image> a = pool.take(16, 8, PixelType::U8);
  EXPECT_EQ(a->width, 16);
  EXPECT_EQ(a->height, 8);
  EXPECT_EQ(a->bytes.size(), 16u * 8 * 4);
  const uint8_t* first = a->bytes.data();
  std::shared_ptr<Image> alsoA = a;  // the last copy decides
  a.reset();
  const std::shared_ptr<Image> b = pool.take(16, 8, PixelType::U8);
  EXPECT_NE(b->bytes.data(), first) << "still held";
  alsoA.reset();
  EXPECT_EQ(pool.take(16, 8, PixelType::U8)->bytes.data(), first);
  const std::shared_ptr<Image> other = pool.take(16, 8, PixelType::F32);
  EXPECT_NE(other->bytes.data(), first);
  EXPECT_EQ(other->bytes.size(), 16u * 8 * 16);
}

TEST(ImagePool, ABatchIsDistinctImagesAndComesBackWhole) {
  ImagePool pool;
  std::set<const uint8_t*> seen;
  {
    const auto batch = pool.take(5, 12, 4, PixelType::U8);
    ASSERT_EQ(batch.size(), 5u);
    for (const auto& image : batch) {
      EXPECT_EQ(image->width, 12);
      EXPECT_EQ(image->height, 4);
      seen.insert(image->bytes.data());
    }
    EXPECT_EQ(seen.size(), 5u);
  }
  const auto again = pool.take(6, 12, 4, PixelType::U8);
  const size_t reused = size_t(std::count_if(again.begin(), again.end(), [&](const auto& image) {
    return seen.count(image->bytes.data()) > 0;
  }));
  EXPECT_EQ(reused, 5u);  // and one new
  EXPECT_TRUE(pool.take(0, 12, 4, PixelType::U8).empty());
}

TEST(ImagePool, AnImageMayOutliveItsPool) {
  std::shared_ptr<Image> kept;
  {
    ImagePool pool;
    kept = pool.take(4, 4, PixelType::U8);
  }
  kept->bytes[0] = 7;  // still valid; freed when let go (sanitizers check)
  kept.reset();
}

}  // namespace
}  // namespace mvr
