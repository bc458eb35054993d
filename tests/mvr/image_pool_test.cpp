// The image pool: images come back once their last user lets go and are
// handed out again for the same shape only; one may outlive the pool.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <set>

#include "mvr/image_pool.h"

namespace mvr {
namespace {

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
