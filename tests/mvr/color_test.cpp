// The sRGB transfer function and its exact 8-bit quantiser (mvr/color.h).
#include <gtest/gtest.h>

#include <cmath>

#include "mvr/color.h"
#include "mvr/image.h"

namespace mvr {
namespace {

double encodeByHand(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055; }

TEST(Srgb, KnownValuesOfTheStandard) {
  EXPECT_FLOAT_EQ(srgbEncode(0.0f), 0.0f);
  EXPECT_FLOAT_EQ(srgbEncode(1.0f), 1.0f);
  EXPECT_NEAR(srgbEncode(0.0031308f), 0.04045f, 1e-5f);  // where the two pieces meet
  EXPECT_NEAR(srgbEncode(0.2158605f), 0.5019608f, 1e-5f);  // byte 128
  EXPECT_NEAR(srgbDecode(srgbEncode(0.37f)), 0.37f, 1e-6f);
  EXPECT_EQ(srgbEncode(-1.0f), 0.0f);
  EXPECT_EQ(srgbEncode(2.0f), 1.0f);
}

TEST(Srgb, Quantiser8IsRoundToNearestOfTheEncoding) {
  // Dense sweep: the table and one comparison must give round(encode * 255)
  // except where that value is within float rounding of a tie.
  int ties = 0;
  for (int i = 0; i <= 2000000; ++i) {
    const double v = i / 2e6;
    const double scaled = 255.0 * encodeByHand(v);
    const int want = int(std::lround(scaled));
    if (srgb8(float(v)) == want) continue;
    ++ties;
    EXPECT_LT(std::abs(scaled - std::floor(scaled) - 0.5), 1e-4) << "v = " << v;
  }
  EXPECT_LT(ties, 20);
  for (int b = 0; b < 256; ++b) EXPECT_EQ(srgb8(linearOfSrgb8(uint8_t(b))), b) << "round trip of " << b;
  EXPECT_EQ(srgb8(NAN), 0);
  EXPECT_EQ(srgb8(-0.5f), 0);
  EXPECT_EQ(srgb8(7.0f), 255);
  // The dark tones keep their levels: linear 1/255 is sRGB byte 13.
  EXPECT_EQ(srgb8(1.0f / 255.0f), 13);
}

TEST(Srgb, ImagesStoreAndReadLinearLight) {
  Image img(2, 1, PixelType::Srgb8);
  img.setLinear(0, 0, {0.2158605f, 0.0f, 1.0f, 0.5f});
  EXPECT_EQ(img.row(0)[0], 128);
  EXPECT_EQ(img.row(0)[3], 128);  // alpha stays linear: round(0.5 * 255)
  EXPECT_NEAR(img.linear(0, 0).r, 0.2158605f, 1e-6f);
  EXPECT_NEAR(img.pixel(0, 0).r, 128.0f / 255.0f, 1e-6f);  // stored value
  Image lin(1, 1, PixelType::U8);
  lin.setLinear(0, 0, {0.2158605f, 0, 0, 1});
  EXPECT_EQ(lin.row(0)[0], 55);
}

}  // namespace
}  // namespace mvr
