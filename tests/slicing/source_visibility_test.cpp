// Parallax, conservative visibility and hole counting for the image-based
// back end, on layers built by hand. Camera: image plane at distance 4,
// 2 units wide over 64 pixels (32 pixels per unit), track [-1, 1].
#include <gtest/gtest.h>

#include "slicing/source_visibility.h"

namespace mvr {
namespace {

ShearingCamera camera() {
  CameraSpec spec;
  spec.distance = 4, spec.planeWidth = 2, spec.nearDistance = 1, spec.farDistance = 8;
  spec.trackLeft = -1, spec.trackRight = 1;
  return ShearingCamera(spec, 64, 2, 5);
}

float depthAt(const ShearingCamera& cam, double Z) { return float(cam.project({0.0, 0.0, Z}, 0).z); }

SourceLayer layerAt(double eyeX, int index) {
  SourceLayer l;
  l.eye = {eyeX, 0.0};
  l.layer = index;
  l.color = Image(64, 2, PixelType::F32);
  l.depth.assign(128, 0.0f);
  return l;
}

void fill(SourceLayer& l, int from, int to, float depth) {
  for (int j = 0; j < 2; ++j)
    for (int x = from; x < to; ++x) l.depth[size_t(j) * 64 + x] = depth;
}

TEST(TrackParallax, APointInFrontMovesAgainstTheEyeOneOnThePlaneStays) {
  const ShearingCamera cam = camera();
  const TrackParallax p(cam);
  // Z = 2: (E - S)(1 - D / (D - Z)) W / Wp = 1 * (1 - 2) * 32.
  EXPECT_NEAR(p.shift(depthAt(cam, 2.0), 0.0, 1.0), -32.0, 1e-3);
  EXPECT_NEAR(p.shift(depthAt(cam, 0.0), -1.0, 1.0), 0.0, 1e-4);
  EXPECT_NEAR(p.shift(depthAt(cam, -4.0), 1.0, 0.0), -16.0, 1e-3);  // w = 8: 1/2 of 32 back
  EXPECT_DOUBLE_EQ(p.reach(0.0), 1.0);
  EXPECT_DOUBLE_EQ(p.reach(-1.0), 2.0);
}

TEST(SourceVisibility, ABackPixelIsDroppedOnlyWhereTheFrontHidesItFromTheWholeTrack) {
  const ShearingCamera cam = camera();
  SourceLayer front = layerAt(0.0, 0), back = layerAt(0.0, 1);
  fill(front, 0, 64, depthAt(cam, 0.0));  // a wall on the image plane
  // One unit behind it (w = 5) a pixel moves 32 (1 - 4/5) = 6.4 pixels
  // against the wall at the track's ends: radius ceil(6.4) + 1 = 8.
  const float behind = depthAt(cam, -1.0);
  for (int x : {5, 30, 56}) back.depth[x] = behind;
  EXPECT_EQ(hideInvisible(front, back, cam, 0.25f), 2);
  EXPECT_EQ(back.depth[30], 0.0f);   // 22..38 covered: hidden
  EXPECT_EQ(back.depth[5], behind);  // the image's edge is within 8 pixels
  EXPECT_EQ(back.depth[56], behind);
  // A hole in the wall 8 pixels away, then a crack where the wall steps
  // forward by a quarter unit (8 pixels of relative motion > 2 x 0.25).
  back.depth[30] = behind;
  front.depth[38] = 0.0f;
  EXPECT_EQ(hideInvisible(front, back, cam, 0.25f), 3);
  front.depth[38] = depthAt(cam, 0.0);
  fill(front, 36, 64, depthAt(cam, 0.25));
  EXPECT_EQ(hideInvisible(front, back, cam, 0.25f), 3);
}

TEST(SourceVisibility, HolesAreGapsNoSourceSawIntoAndBackgroundIsNot) {
  const ShearingCamera cam = camera();
  // Both ends see a block one unit in front (w = 3) over pixels 20..27 and
  // a wall on the image plane around it. In the middle the block moves
  // 32 (1 - 4/3) = -10.7 pixels from the left end and +10.7 from the
  // right: the wall behind pixels 20..27 shows, and no source saw it.
  const float wall = depthAt(cam, 0.0), block = depthAt(cam, 1.0);
  SourceLayer left = layerAt(-1.0, 0), right = layerAt(1.0, 0);
  for (SourceLayer* l : {&left, &right}) {
    fill(*l, 0, 64, wall);
    fill(*l, 20, 28, block);
  }
  EXPECT_EQ(countHoles({&left, &right}, cam, 0.0, 0.0f), 16);  // 8 per scanline
  // A second layer from the left that saw behind the block fills them.
  SourceLayer behind = layerAt(-1.0, 1);
  fill(behind, 20, 28, wall);
  EXPECT_EQ(countHoles({&left, &right, &behind}, cam, 0.0, 0.0f), 0);
  // Where one source sees background through the gap (a window in the
  // wall), the gap is background, not a hole.
  fill(right, 20, 28, 0.0f);
  EXPECT_EQ(countHoles({&left, &right}, cam, 0.0, 0.0f), 0);
}

}  // namespace
}  // namespace mvr
