// PSTs worked out by hand (docs/CONVENTIONS.md: corners at r = 0 and r = N).
#include <gtest/gtest.h>

#include "epi/pst.h"

namespace mvr {
namespace {

SliceEnd end(float x0, float dx, float depth = 0.5f) {
  return {x0, dx, depth, 1.0f, glm::vec3(1, 0, 0), glm::vec3(0, 0, 1)};
}

TEST(Pst, UntwistedTrackIsOneFrontPiece) {
  Pst p = makePst(end(10, 1), end(20, 1), 4, false);
  ASSERT_EQ(p.pieceCount, 1);
  EXPECT_EQ(p.pieces[0].rTop, 0.0f);
  EXPECT_EQ(p.pieces[0].rBottom, 4.0f);
  EXPECT_TRUE(p.pieces[0].front);
  // Corners half a view beyond the extreme views: x0(0) = 10 - 0.5.
  EXPECT_FLOAT_EQ(p.x0(0), 9.5f);
  EXPECT_FLOAT_EQ(p.x1(4), 23.5f);
  EXPECT_FLOAT_EQ(p.width(0), p.width(4));
}

TEST(Pst, TwistedTrackWithoutCrossingStaysWhole) {
  Pst p = makePst(end(10, 1), end(20, 3), 4, true);
  ASSERT_EQ(p.pieceCount, 1);
  EXPECT_FLOAT_EQ(p.width(0), 9.0f);   // (20 - 1.5) - (10 - 0.5)
  EXPECT_FLOAT_EQ(p.width(4), 17.0f);  // (20 + 10.5) - (10 + 3.5)
}

TEST(Pst, CrossingAtAViewSplitsThere) {
  // dL = (14 + 1) - (10 - 1) = 6; dR = (14 - 7) - (10 + 7) = -10;
  // r* = 4 * 6 / 16 = 1.5: exactly view 1's row centre.
  Pst p = makePst(end(10, 2), end(14, -2), 4, false);
  ASSERT_EQ(p.pieceCount, 2);
  EXPECT_FLOAT_EQ(p.pieces[0].rBottom, 1.5f);
  EXPECT_FLOAT_EQ(p.pieces[1].rTop, 1.5f);
  EXPECT_TRUE(p.pieces[0].front);
  EXPECT_FALSE(p.pieces[1].front);
  EXPECT_NEAR(p.width(1.5f), 0.0f, 1e-5);
}

TEST(Pst, CrossingBetweenViewsSplitsThere) {
  // r = 0: x0 = 9.5, x1 = 17.5 -> dL = 8; r = 3: x0 = 12.5, x1 = 8.5 -> dR = -4;
  // r* = 3 * 8 / 12 = 2: between the centres of views 1 (1.5) and 2 (2.5).
  Pst p = makePst(end(10, 1), end(16, -3), 3, false);
  ASSERT_EQ(p.pieceCount, 2);
  EXPECT_NEAR(p.pieces[0].rBottom, 2.0f, 1e-5);
  EXPECT_NEAR(p.x0(2.0f), p.x1(2.0f), 1e-5);
}

TEST(Pst, BackPieceIsCulledWhenAsked) {
  Pst p = makePst(end(10, 2), end(14, -2), 4, true);
  ASSERT_EQ(p.pieceCount, 1);
  EXPECT_TRUE(p.pieces[0].front);
  EXPECT_FLOAT_EQ(p.pieces[0].rBottom, 1.5f);
  Pst back = makePst(end(20, 0), end(10, 0), 4, true);
  EXPECT_EQ(back.pieceCount, 0);
}

TEST(Pst, OneViewHasNoTrack) {
  Pst p = makePst(end(10, 0), end(12, 0), 1, false);
  ASSERT_EQ(p.pieceCount, 1);
  EXPECT_EQ(p.pieces[0].rBottom, 1.0f);
  EXPECT_FLOAT_EQ(p.x0(0.5f), 10.0f);
}

TEST(Pst, TwoViews) {
  Pst p = makePst(end(10, 4), end(12, 4), 2, false);
  ASSERT_EQ(p.pieceCount, 1);
  EXPECT_FLOAT_EQ(p.x0(0.5f), 10.0f);  // view 0
  EXPECT_FLOAT_EQ(p.x0(1.5f), 14.0f);  // view 1
  EXPECT_FLOAT_EQ(p.x0(0.0f), 8.0f);   // extrapolated corner
}

TEST(Pst, DegenerateSliceHasNoPieces) {
  EXPECT_EQ(makePst(end(10, 1), end(10, 1), 8, false).pieceCount, 0);
}

TEST(Pst, ColourIsHyperbolicAndDepthLinearInU) {
  SliceEnd a = end(0, 0, 0.2f), b = end(10, 0, 0.6f);
  a.invW = 1.0f;         // w = 1
  b.invW = 0.25f;        // w = 4
  a.frontOverW = glm::vec3(1, 0, 0) * a.invW;
  b.frontOverW = glm::vec3(0, 1, 0) * b.invW;
  Pst p = makePst(a, b, 1, false);
  // Halfway on screen is s = 0.2 in 3D: u = s iw0 / ((1 - s) iw1 + s iw0) = 0.2 / 0.4 = 0.5.
  glm::vec3 c = pstColor(p, true, 0.5f);
  EXPECT_NEAR(c.r, 0.8f, 1e-6);
  EXPECT_NEAR(c.g, 0.2f, 1e-6);
  EXPECT_NEAR(pstDepth(p, 0.5f), 0.4f, 1e-6);
}

}  // namespace
}  // namespace mvr
