// Image slices by hand: unprojection inverts the camera, a pixel on the
// image plane has zero disparity and one in front a known track, runs
// coalesce, silhouettes keep their pixel boundary.
#include <gtest/gtest.h>
#include <glm/gtc/constants.hpp>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include "apps/cli/cli.h"
#include "apps/scenes/test_scenes.h"
#include "mvr/backends/interp/interp_renderer.h"
#include "mvr/error.h"
#include "mvr/assets/scene_io.h"
#include "mvr/views/fragment_lists.h"
#include "mvr/views/source_layers.h"
#include "slicing/image_slices.h"
#include "tests/support/meshes.h"
#include "tests/support/render_helpers.h"

namespace mvr {
namespace {

TEST(ImageSlices, UnprojectInvertsTheCamera) {
  CameraSpec spec;
  spec.distance = 5, spec.planeWidth = 3, spec.nearDistance = 2, spec.farDistance = 9;
  spec.trackLeft = -2, spec.trackRight = 2;
  ShearingCamera cam(spec, 64, 48, 5);
  const glm::dvec3 p(0.4, -0.3, 1.1);
  for (int view : {0, 3}) {
    const glm::dvec3 w = cam.project(p, view);
    const glm::dvec3 q = cam.unprojectAt(cam.viewX(view), 0.0, w);
    EXPECT_NEAR(glm::length(q - p), 0.0, 1e-9);
  }
}

TEST(ImageSlices, APixelOnTheImagePlaneStaysPutAndOneInFrontMoves) {
  CameraSpec spec;
  spec.distance = 4, spec.planeWidth = 2, spec.nearDistance = 1, spec.farDistance = 8;
  spec.trackLeft = -1, spec.trackRight = 1;
  ShearingCamera cam(spec, 16, 4, 3);
  // Two pixels of scanline 1 seen from the middle: one on the image plane
  // (zero disparity), one at Z = 2 (moves -(W/Wp) Z/(D - Z) = -8 px per unit).
  SourceLayer layer;
  layer.eye = {0.0, 0.0};
  layer.color = Image(16, 4, PixelType::F32);
  layer.depth.assign(16 * 4, 0.0f);
  auto depthAt = [&](double Z) { return cam.project({0.0, 0.0, Z}, 0).z; };
  layer.depth[1 * 16 + 5] = float(depthAt(0.0));
  layer.depth[1 * 16 + 9] = float(depthAt(2.0));
  const ImageSlices s = sliceSourceLayers({layer}, cam, 0, {.overlap = 0.0f});
  ASSERT_EQ(s.table.sliceCount(), 2u);
  ASSERT_EQ(s.table.scanline(1).size(), 2u);
  auto [a0, a1] = sliceEnds(s.vertices, s.table.scanline(1)[0]);
  auto [b0, b1] = sliceEnds(s.vertices, s.table.scanline(1)[1]);
  // Row coordinate r: x = x0 + (r - 0.5) dx; view 1 (the middle) at r = 1.5.
  EXPECT_NEAR(a0.x0 + a0.dx, 5.0f, 1e-4f);
  EXPECT_NEAR(a1.x0 + a1.dx, 6.0f, 1e-4f);
  EXPECT_NEAR(a0.dx, 0.0f, 1e-5f);
  EXPECT_NEAR(b0.x0 + b0.dx, 9.0f, 1e-4f);
  EXPECT_NEAR(b0.dx, -8.0f, 1e-4f);  // one unit of track per view
  EXPECT_NEAR(b1.x0 - b0.x0, 1.0f, 1e-4f);  // the same width in every view
}

// One scanline of a 16 x 2 layer seen from the middle of a 2-unit track
// (image plane at distance 4, 2 units wide: 8 pixels per unit).
struct RunCase {
  ShearingCamera cam = [] {
    CameraSpec spec;
    spec.distance = 4, spec.planeWidth = 2, spec.nearDistance = 1, spec.farDistance = 8;
    spec.trackLeft = -1, spec.trackRight = 1;
    return ShearingCamera(spec, 16, 2, 3);
  }();
  SourceLayer layer;
  RunCase() {
    layer.color = Image(16, 2, PixelType::F32);
    layer.depth.assign(32, 0.0f);
  }
  float depthAt(double Z) const { return float(cam.project({0.0, 0.0, Z}, 0).z); }
  void set(int x, double Z, float grey) {
    layer.depth[x] = depthAt(Z);
    float* px = reinterpret_cast<float*>(layer.color.row(0)) + 4 * x;
    px[0] = px[1] = px[2] = grey, px[3] = 1.0f;
  }
};

TEST(ImageSlices, CoalescingMergesAlignedRunsOfCloseDepth) {
  RunCase c;
  for (int x = 0; x < 7; ++x) c.set(x, 0.0, x / 10.0f);  // on the image plane
  c.set(8, 0.0, 0.5f);
  c.set(9, 1.0, 0.5f);  // a unit in front: 8 / 3 pixels of parallax at the track's ends
  EXPECT_EQ(sliceSourceLayers({c.layer}, c.cam, 0, {.coalesce = 0.0f}).table.sliceCount(), 9u);
  // Aligned blocks of 4, 2 and 1 pixels, then 8 and 9 apart (their depths
  // differ by far more than half a pixel of parallax).
  const ImageSlices s = sliceSourceLayers({c.layer}, c.cam, 0, {.overlap = 0.25f, .coalesce = 0.5f});
  ASSERT_EQ(s.table.sliceCount(), 5u);
  EXPECT_EQ(s.pixels, 9u);
  const std::vector<int> lengths = {4, 2, 1, 1, 1};
  for (size_t k = 0; k < lengths.size(); ++k) EXPECT_EQ(s.vertices.vectors[k].length, lengths[k]) << k;
  // The block of four: ends at x = -1/4 (widened beyond the image's edge)
  // and 4 (the boundary it shares with the next block, which starts there),
  // u from -1/16 to 1, its texels the pixels' colours.
  const SliceVector& v = s.vertices.vectors[0];
  EXPECT_FLOAT_EQ(v.u0, -0.0625f);
  EXPECT_FLOAT_EQ(v.u1, 1.0f);
  EXPECT_FLOAT_EQ(s.vertices.vectorTexels.texels()[v.base + 3].r, 0.3f);
  auto [e0, e1] = sliceEnds(s.vertices, s.table.scanline(0)[0]);
  EXPECT_NEAR(e0.x0 + e0.dx, -0.25f, 1e-4f);  // the middle view is the source
  EXPECT_NEAR(e1.x0 + e1.dx, 4.0f, 1e-4f);
  auto [n0, n1] = sliceEnds(s.vertices, s.table.scanline(0)[1]);
  EXPECT_NEAR(n0.x0 + n0.dx, 4.0f, 1e-4f);
  // A unit of depth is 8 / 3 pixels: merging 8 and 9 needs T >= 8/3.
  const float range = coalesceDepthRange(c.cam, 0.0, 1.0f);
  EXPECT_NEAR(c.depthAt(1.0) - c.depthAt(0.0), 8.0f / 3.0f * range, 1e-5f);
  EXPECT_EQ(sliceSourceLayers({c.layer}, c.cam, 0, {.coalesce = 2.7f}).table.sliceCount(), 4u);
}

// No footprint widens inside the image: a silhouette pixel ends on its
// pixel boundary (issue 18), and two pixels of one surface end on the
// boundary they share, at the mean of their depths, so that their tracks
// meet in every view.
TEST(ImageSlices, SilhouettesKeepThePixelBoundary) {
  RunCase c;
  c.set(3, 0.0, 0.5f);  // alone between empty pixels
  c.set(7, 0.0, 0.5f);
  c.set(8, 0.1, 0.5f);  // continues 7 (0.27 pixels of parallax apart): they share x = 8
  c.set(9, 1.0, 0.5f);  // a unit in front of 8: 8/3 pixels of parallax over the track, a step
  const ImageSlices s = sliceSourceLayers({c.layer}, c.cam, 0, {.overlap = 0.25f});
  ASSERT_EQ(s.table.sliceCount(), 4u);
  const float want[4][2] = {{3.0f, 4.0f}, {7.0f, 8.0f}, {8.0f, 9.0f}, {9.0f, 10.0f}};
  auto [a0, a1] = sliceEnds(s.vertices, s.table.scanline(0)[1]);
  auto [b0, b1] = sliceEnds(s.vertices, s.table.scanline(0)[2]);
  EXPECT_FLOAT_EQ(a1.depth, 0.5f * (c.layer.depth[7] + c.layer.depth[8]));
  EXPECT_FLOAT_EQ(b0.depth, a1.depth);
  EXPECT_NEAR(a1.dx, b0.dx, 1e-6f);  // the same point: the same track
  for (int k = 0; k < 4; ++k) {
    auto [e0, e1] = sliceEnds(s.vertices, s.table.scanline(0)[size_t(k)]);
    EXPECT_NEAR(e0.x0 + e0.dx, want[k][0], 1e-4f) << k;  // the middle view is the source
    EXPECT_NEAR(e1.x0 + e1.dx, want[k][1], 1e-4f) << k;
    const SliceVector& v = s.vertices.vectors[size_t(k)];
    EXPECT_FLOAT_EQ(v.u0, want[k][0] - std::floor(want[k][0] + 0.5f));
  }
}

// A rim whose depth profile is the parabola u = ue - a (z - zt)^2 (u in
// pixels from the rim pixel's centre, outward): with fitRims the rim
// pixel's outer end is the parabola's vertex, at the tangent depth.
TEST(ImageSlices, ARimEndsWhereItsSurfaceCurvatureSaysTheSilhouetteIs) {
  RunCase c;
  const double ue = 0.3, a = 1e4, zt = c.depthAt(0.0);
  for (int k = 0; k <= 4; ++k) {  // pixels 10 (the rim) down to 6
    c.set(10 - k, 0.0, 0.5f);
    c.layer.depth[size_t(10 - k)] = float(zt + std::sqrt((ue + k) / a));
  }
  auto rightEnd = [&](bool fit) {
    const ImageSlices s = sliceSourceLayers({c.layer}, c.cam, 0, {.overlap = 0.25f, .fitRims = fit});
    return sliceEnds(s.vertices, s.table.scanline(0).back()).second;
  };
  const SliceEnd fitted = rightEnd(true), plain = rightEnd(false);
  EXPECT_NEAR(fitted.x0 + fitted.dx, 10.5 + ue, 1e-3);  // the middle view is the source
  EXPECT_NEAR(fitted.depth, zt, 1e-5);
  EXPECT_NEAR(plain.x0 + plain.dx, 11.0, 1e-4);  // the pixel's boundary
  // A plane ends at a crease: no curvature, the boundary stays.
  for (int k = 0; k <= 4; ++k) c.layer.depth[size_t(10 - k)] = float(zt + 1e-3 * k);
  EXPECT_NEAR(rightEnd(true).x0 + rightEnd(true).dx, 11.0, 1e-4);
}

// With the source's outline sampled finer, a silhouette pixel's outer end
// is its outermost covered sample's edge at that sample's depth; an end
// toward a covered neighbour, or a pixel without samples, is as before.
TEST(ImageSlices, ASilhouetteEndsOnTheFinerOutline) {
  RunCase c;
  for (int x = 4; x <= 6; ++x) c.set(x, 0.0, 0.5f);
  c.layer.outline.assign(32, PixelOutline{});
  const float front = c.depthAt(0.25), back = c.depthAt(-0.25);
  c.layer.outline[4] = {0.375f, back, 1.0f, c.layer.depth[4]};
  c.layer.outline[6] = {0.0f, c.layer.depth[6], 0.625f, front};
  auto ends = [&](const SourceLayer& layer) {
    const ImageSlices s = sliceSourceLayers({layer}, c.cam, 0, {.overlap = 0.25f});
    std::vector<SliceEnd> e;
    for (const Slice& slice : s.table.scanline(0)) {
      auto [a, b] = sliceEnds(s.vertices, slice);
      e.push_back(a), e.push_back(b);
    }
    return std::pair(e, s.vertices.vectors);
  };
  const auto [fine, vectors] = ends(c.layer);
  ASSERT_EQ(fine.size(), 6u);
  auto x = [](const SliceEnd& e) { return e.x0 + e.dx; };  // the middle view is the source
  EXPECT_NEAR(x(fine[0]), 4.375f, 1e-4f);
  EXPECT_FLOAT_EQ(fine[0].depth, back);
  EXPECT_NEAR(x(fine[1]), 5.0f, 1e-4f);  // toward 5: the boundary they share
  EXPECT_NEAR(x(fine[5]), 6.625f, 1e-4f);
  EXPECT_FLOAT_EQ(fine[5].depth, front);
  EXPECT_FLOAT_EQ(vectors[0].u0, 0.375f);  // the texel spans the pixel still
  EXPECT_FLOAT_EQ(vectors[2].u1, 0.625f);
  // A layer behind, of the same source: on the nearest layer's outline ray,
  // three quarters of the way from its silhouette point to its own depth.
  SourceLayer behind = c.layer;
  behind.layer = 1;
  behind.outline.clear();
  behind.depth.assign(32, 0.0f);
  behind.depth[6] = c.depthAt(-0.5);
  const ImageSlices both = sliceSourceLayers({c.layer, behind}, c.cam, 0, {.overlap = 0.25f});
  ASSERT_EQ(both.table.sliceCount(), 4u);
  auto [b0, b1] = sliceEnds(both.vertices, both.table.scanline(0)[3]);
  // Toward 5, a hole of this layer (covered in front): its boundary.
  EXPECT_NEAR(x(b0), 6.0f, 1e-4f);
  // Toward a step of its own (5 far behind it): a quarter pixel in.
  SourceLayer stepped = behind;
  stepped.depth[5] = c.depthAt(-3.0);
  const ImageSlices step = sliceSourceLayers({c.layer, stepped}, c.cam, 0, {.overlap = 0.25f});
  ASSERT_EQ(step.table.sliceCount(), 5u);
  auto [s0, s1] = sliceEnds(step.vertices, step.table.scanline(0)[4]);
  EXPECT_NEAR(x(s0), 6.25f, 1e-4f);
  EXPECT_FLOAT_EQ(step.vertices.vectors[4].u0, 0.25f);
  EXPECT_NEAR(x(b1), 6.625f, 1e-4f);
  EXPECT_NEAR(b1.depth, front + 0.75f * (behind.depth[6] - front), 1e-6f);
  // The outline in the empty neighbour's near half (covered samples short
  // of pixel 3's centre): the front's end goes there, a layer behind stops
  // a quarter pixel inside its own pixel, where the front's ray runs inside.
  SourceLayer beyond = c.layer;
  beyond.outline[4].left = -0.375f;
  const auto [wide, wideVectors] = ends(beyond);
  EXPECT_NEAR(x(wide[0]), 3.625f, 1e-4f);
  EXPECT_FLOAT_EQ(wideVectors[0].u0, -0.375f);
  behind.depth[4] = c.depthAt(-0.5);
  const ImageSlices deeper = sliceSourceLayers({beyond, behind}, c.cam, 0, {.overlap = 0.25f});
  ASSERT_EQ(deeper.table.sliceCount(), 5u);
  auto [d0, d1] = sliceEnds(deeper.vertices, deeper.table.scanline(0)[3]);
  EXPECT_NEAR(x(d0), 4.25f, 1e-4f);
  EXPECT_NEAR(d0.depth, back + 0.75f * (behind.depth[4] - back), 1e-6f);
  // Nothing sampled: the pixel's boundary at its centre's depth.
  SourceLayer none = c.layer;
  none.outline[6] = PixelOutline{};
  const auto [coarse, v2] = ends(none);
  EXPECT_NEAR(x(coarse[5]), 7.0f, 1e-4f);
  EXPECT_FLOAT_EQ(coarse[5].depth, c.layer.depth[6]);
}

// A lone pixel between two covered neighbours too far in depth to join
// (a surface seen steeply) lies on the gentler of its one-sided slopes;
// at a step (one side level) it stays flat.
TEST(ImageSlices, SteepFootprintsTakeTheGentlerSlope) {
  RunCase c;
  const double Z[5] = {0.0, 0.8, 1.4, 1.7, 1.7};  // pixels 4..8: steep, steeper before, then level
  for (int k = 0; k < 5; ++k) c.set(4 + k, Z[k], 0.5f);
  const ImageSlices s = sliceSourceLayers({c.layer}, c.cam, 0, {.overlap = 0.25f});
  ASSERT_EQ(s.table.sliceCount(), 5u);
  auto depths = [&](int k) {
    auto [a, b] = sliceEnds(s.vertices, s.table.scanline(0)[size_t(k)]);
    return std::pair(a.depth, b.depth);
  };
  const float* d = c.layer.depth.data() + 4;
  // Pixel 6 (k = 2): slopes 1 -> 2 and 2 -> 3, the second gentler.
  const float slope = d[3] - d[2];
  ASSERT_LT(std::abs(slope), std::abs(d[2] - d[1]));
  EXPECT_NEAR(depths(2).first, d[2] - 0.5f * slope, 1e-6f);
  EXPECT_NEAR(depths(2).second, d[2] + 0.5f * slope, 1e-6f);
  // Pixel 7 (k = 3): level toward 8, a step from 6: flat.
  EXPECT_FLOAT_EQ(depths(3).first, d[3]);
  EXPECT_FLOAT_EQ(depths(3).second, d[3]);
}

TEST(ImageSlices, ARunOnATiltedPlaneKeepsItsPixelsInPlace) {
  // Eight pixels of a plane tilted in depth: one slice whose ends sit on
  // the line through the first and last pixel centres, so every pixel's
  // track is where its own slice would put it.
  RunCase c;
  for (int x = 0; x < 8; ++x) c.layer.depth[x] = c.depthAt(0.0) + 0.001f * float(x);
  const ImageSlices one = sliceSourceLayers({c.layer}, c.cam, 0, {.overlap = 0.0f, .coalesce = 100.0f});
  const ImageSlices each = sliceSourceLayers({c.layer}, c.cam, 0, {.overlap = 0.0f});
  ASSERT_EQ(one.table.sliceCount(), 1u);
  auto [a0, a1] = sliceEnds(one.vertices, one.table.scanline(0)[0]);
  auto [f0, f1] = sliceEnds(each.vertices, each.table.scanline(0)[0]);
  auto [l0, l1] = sliceEnds(each.vertices, each.table.scanline(0)[7]);
  for (float r : {0.0f, 3.0f}) {  // the track's ends
    // Pixel centres 0.5 and 7.5 are 1/16 and 15/16 of the way along.
    const float x0 = a0.x0 + (r - 0.5f) * a0.dx, x1 = a1.x0 + (r - 0.5f) * a1.dx;
    EXPECT_NEAR(x0 + (x1 - x0) / 16.0f, f0.x0 + (r - 0.5f) * f0.dx + 0.5f * (f1.x0 - f0.x0), 2e-3f);
    EXPECT_NEAR(x0 + (x1 - x0) * 15.0f / 16.0f, l0.x0 + (r - 0.5f) * l0.dx + 0.5f * (l1.x0 - l0.x0), 2e-3f);
  }
}

}  // namespace
}  // namespace mvr
