// The display transforms (mvr/tone_map.h) at values worked by hand from
// the published formulas three.js uses, and an F32 frame tone mapped into
// 8-bit sRGB.
#include <gtest/gtest.h>

#include "mvr/color.h"
#include "mvr/frames/tone_mapped_renderer.h"
#include "mvr/image.h"
#include "mvr/tone_map.h"

namespace mvr {
namespace {

void expectNear(const glm::vec3& a, const glm::vec3& b, float tolerance) {
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(a[k], b[k], tolerance) << k;
}

TEST(ToneMap, NeutralIsTheIdentityLessItsOffsetBelowTheShoulder) {
  // min 0.2 >= 0.08: offset 0.04; the peak 0.46 is below 0.76.
  expectNear(toneMap(ToneMap::Neutral, {0.5f, 0.3f, 0.2f}), {0.46f, 0.26f, 0.16f}, 1e-6f);
  // min 0.05: offset 0.05 - 6.25 * 0.05^2.
  expectNear(toneMap(ToneMap::Neutral, {0.3f, 0.1f, 0.05f}), glm::vec3(0.3f, 0.1f, 0.05f) - 0.034375f, 1e-6f);
  // Grey 2: 1.96 after the offset, compressed to 1 - 0.24^2 / 1.44 = 0.96.
  expectNear(toneMap(ToneMap::Neutral, glm::vec3(2.0f)), glm::vec3(0.96f), 1e-5f);
  // Very bright: towards 1, never past it.
  const glm::vec3 c = toneMap(ToneMap::Neutral, glm::vec3(1e4f, 5e3f, 1e3f));
  EXPECT_LE(c.r, 1.0f);
  EXPECT_GT(c.r, 0.99f);
}

TEST(ToneMap, AcesAndAgxKeepGreyGrey) {
  // Both matrices' rows sum to 1: grey 0.18 is the fit at 0.18 / 0.6 for
  // ACES (0.2131) and for AgX the sigmoid at (log2 0.18 + 12.47) / 16.5 =
  // 0.6061, to the power 2.2 (0.2145).
  expectNear(toneMap(ToneMap::Aces, glm::vec3(0.18f)), glm::vec3(0.213105f), 1e-4f);
  expectNear(toneMap(ToneMap::Agx, glm::vec3(0.18f)), glm::vec3(0.214519f), 1e-3f);
  EXPECT_EQ(toneMap(ToneMap::Aces, glm::vec3(0.0f)).r, 0.0f);  // clamped at 0: the fit dips below
  EXPECT_LE(toneMap(ToneMap::Aces, glm::vec3(100.0f)).r, 1.0f);
  EXPECT_LE(toneMap(ToneMap::Agx, glm::vec3(100.0f)).g, 1.0f);
  EXPECT_EQ(toneMap(ToneMap::None, glm::vec3(3.0f)), glm::vec3(3.0f));
}

TEST(ToneMap, NamesRoundTrip) {
  for (ToneMap m : {ToneMap::None, ToneMap::Aces, ToneMap::Agx, ToneMap::Neutral})
    EXPECT_EQ(toneMapNamed(toneMapName(m)), m);
  EXPECT_FALSE(toneMapNamed("filmic"));
}

TEST(ToneMap, AFloatFrameBecomesSrgbBytes) {
  Image hdr(2, 1, PixelType::F32);
  float* f = reinterpret_cast<float*>(hdr.bytes.data());
  const float values[8] = {0.5f, 0.3f, 0.2f, 1.0f, 2.0f, 2.0f, 2.0f, 0.5f};
  std::copy(values, values + 8, f);
  Image out(2, 1, PixelType::Srgb8);
  toneMapImage(hdr, ToneMap::Neutral, out);
  EXPECT_EQ(out.bytes[0], srgb8(0.46f));
  EXPECT_EQ(out.bytes[2], srgb8(0.16f));
  EXPECT_EQ(out.bytes[4], srgb8(0.96f));
  EXPECT_EQ(out.bytes[7], 128);  // alpha as it is (0.5)
}

}  // namespace
}  // namespace mvr
