// Weights and per-pixel rules of blending two sources (mvr/backends/interp/source_blend.h),
// on EPIs small enough to check by hand.
#include <gtest/gtest.h>

#include "mvr/backends/interp/source_blend.h"

namespace mvr {
namespace {

// Five views between source A (view 0) and source B (view 4).
ShearingCamera interval() { return ShearingCamera(CameraSpec{}, 8, 4, 5); }

TEST(SourceWeight, OneAtTheFirstSourceZeroAtTheOtherHalfBetween) {
  const ShearingCamera cam = interval();
  for (Blend mode : {Blend::Track, Blend::Angular}) {
    // From the middle view, a point near the axis sees both eyes at
    // nearly the same angle.
    EXPECT_NEAR(sourceWeight(mode, cam, 0, 1, 0, 3), 1.0, 1e-12) << nameOf(kBlendNames, mode);
    EXPECT_NEAR(sourceWeight(mode, cam, 0, 1, 4, 3), 0.0, 1e-12) << nameOf(kBlendNames, mode);
    EXPECT_NEAR(sourceWeight(mode, cam, 0, 1, 2, 4), 0.5, 0.01) << nameOf(kBlendNames, mode);
    for (int v = 0; v < 4; ++v)
      EXPECT_GT(sourceWeight(mode, cam, 0, 1, v, 5), sourceWeight(mode, cam, 0, 1, v + 1, 5)) << v;
  }
  EXPECT_DOUBLE_EQ(sourceWeight(Blend::Track, cam, 0, 1, 1, 0), 0.75);
  // The cosine form is flat at both sources: a quarter of the way, more
  // than three quarters of A.
  EXPECT_GT(sourceWeight(Blend::Angular, cam, 0, 1, 1, 4), 0.8);
  EXPECT_DOUBLE_EQ(sourceWeight(Blend::None, cam, 0, 1, 2, 4), 1.0);
}

void put(Image& epi, int x, int v, glm::vec4 c) { epi.setLinear(x, v, c); }

TEST(BlendEpi, MixesOneSurfaceWeightsTheOutlineAndKeepsTheRest) {
  const ShearingCamera cam = interval();
  const int v = 1;  // A's weight 0.75 (track)
  Image a(8, 5, PixelType::F32), b(8, 5, PixelType::F32), joint(8, 5, PixelType::F32);
  const glm::vec4 grey(0.5f, 0.5f, 0.5f, 1.0f), light(0.54f, 0.54f, 0.54f, 1.0f), red(1, 0, 0, 1);
  // x 0: only A covers, B sees background (its empty run reaches the row's
  // end). x 1-3: both, the same surface. x 4: both, different surfaces
  // (the joint's depth test chose B's red). x 5: only A, B has a one-pixel
  // crack (or a hole it could not see into: the joint covers all of it).
  // x 6: only B. x 7: nobody.
  for (int x = 0; x <= 5; ++x) put(a, x, v, grey);
  for (int x = 1; x <= 3; ++x) put(b, x, v, light);
  put(b, 4, v, red);
  for (int x = 0; x <= 5; ++x) put(joint, x, v, x == 4 ? red : grey);
  put(b, 6, v, light);  // the crack's far side
  put(joint, 6, v, light);
  blendEpi(Blend::Track, cam, 0, 1, a, b, joint);
  EXPECT_FLOAT_EQ(joint.linear(0, v).a, 0.75f);  // A's weight as coverage
  EXPECT_FLOAT_EQ(joint.linear(0, v).r, 0.5f);   // straight alpha: the colour stays
  EXPECT_NEAR(joint.linear(2, v).r, 0.75f * 0.5f + 0.25f * 0.54f, 1e-6f);
  EXPECT_FLOAT_EQ(joint.linear(2, v).a, 1.0f);
  EXPECT_EQ(joint.linear(4, v), red);
  EXPECT_EQ(joint.linear(5, v), grey);  // a crack in B is not background
  EXPECT_FLOAT_EQ(joint.linear(6, v).a, 0.25f);  // B alone, A sees background to the end
  EXPECT_EQ(joint.linear(7, v), glm::vec4(0.0f));
}

}  // namespace
}  // namespace mvr
