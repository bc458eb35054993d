// The image-based back end: unprojection by hand, segment slices in the
// slice table, identity at a source view, depth peeling, and quality
// against deferred, the pipeline that renders its source views.
// Tolerances (default scene, 120x90, 5 or 9 views):
//  identity     the centre view of `center` equals deferred's exactly
//  dual         >= 24 dB against deferred in every view (silhouettes
//               dilate by up to half a pixel plus the overlap); better than
//               center at the ends of the track (content center never saw)
#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>

#include "apps/cli.h"
#include "apps/test_scenes.h"
#include "mvr/backends/interp/interp_renderer.h"
#include "mvr/error.h"
#include "mvr/io/scene_io.h"
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

class InterpTest : public test::GlTest {
 protected:
  // The default scene at 120x90 and its views from deferred, the pipeline
  // that renders interp's source views.
  struct Reference {
    explicit Reference(int viewCount)
        : scene(loadScene(test::assetPath("default.json"))), cam(*scene.camera, 120, 90, viewCount),
          views(test::renderViews(*makeDeferredRenderer(scene, PixelType::U8), cam)) {}
    Scene scene;
    ShearingCamera cam;
    test::CaptureSink views;
  };
};

TEST_F(InterpTest, DepthPeelingFindsTheLayersBehindAndStops) {
  Scene scene = loadScene(test::assetPath("default.json"));
  ShearingCamera cam(*scene.camera, 96, 72, 5);
  auto sources = makeSourceLayerRenderer(scene);
  RenderStats stats;
  const double track = cam.spec().trackRight - cam.spec().trackLeft;
  const std::vector<SourceLayer> layers = sources->render(cam, {0.0, 0.0}, 8, track, stats);
  // A closed cup: front wall, inside, back wall... then nothing.
  ASSERT_GE(layers.size(), 2u);
  ASSERT_LT(layers.size(), 8u);
  for (size_t k = 1; k < layers.size(); ++k) {
    EXPECT_LT(layers[k].fragments, layers[k - 1].fragments);
    for (size_t i = 0; i < layers[k].depth.size(); ++i)
      if (layers[k].depth[i] > 0.0f) {
        ASSERT_GT(layers[k - 1].depth[i], layers[k].depth[i]);  // reversed Z: in front is larger
      }
  }
  // A track narrower than a pixel's footprint can show nothing behind.
  EXPECT_EQ(sources->render(cam, {0.0, 0.0}, 8, 1e-6, stats).size(), 1u);
}

// A plane drawn twice in the same place, red then blue, behind a cube:
// every pixel of the plane a tie of depths that the first drawn wins.
Scene coincidentPlanes() {
  const std::string path = ::testing::TempDir() + "/mvr_coincident_planes.json";
  std::ofstream(path) << R"({"meshes": [
    {"file": ")" << test::assetPath("plane.obj") << R"(", "material": {"diffuse": [0.9, 0.1, 0.1]}},
    {"file": ")" << test::assetPath("plane.obj") << R"(", "material": {"diffuse": [0.1, 0.1, 0.9]}},
    {"file": ")" << test::assetPath("cube.obj") << R"(", "transform": {"translate": [0.2, 0.1, 0.5], "scale": 0.4},
     "material": {"diffuse": [0.8, 0.8, 0.8]}}],
    "lights": [{"type": "directional", "direction": [-0.3, -0.4, -1.0], "color": [0.8, 0.8, 0.8]}],
    "camera": {"distance": 5.0, "image_plane": 3.2, "track": [-1.5, 1.5], "near": 3.0, "far": 7.0}})";
  return loadScene(path);
}

// Ten planes one behind the other, facing the camera: ten fragments a
// pixel, more than the fragment lists first make room for.
Scene stackedPlanes() {
  const std::string path = ::testing::TempDir() + "/mvr_stacked_planes.json";
  std::ofstream json(path);
  json << R"({"meshes": [)";
  for (int k = 0; k < 10; ++k)
    json << (k ? "," : "") << R"({"file": ")" << test::assetPath("plane.obj") << R"(", "transform": {"translate": [0, 0, )"
         << 0.5 - 0.12 * k << R"(], "scale": 3}, "material": {"diffuse": [0.5, )" << 0.1 * k << R"(, 0.5]}})";
  json << R"(], "lights": [{"type": "directional", "direction": [0, 0, -1], "color": [1, 1, 1]}],
    "camera": {"distance": 5.0, "image_plane": 3.2, "track": [-1.5, 1.5], "near": 3.0, "far": 7.0}})";
  json.close();
  return loadScene(path);
}

// The fragment lists' layers are the peel's, bit for bit: each a pass of
// the mesh against one pass resolved per layer, on a scene whose layers
// run deep (the cup: front, inside, back, over the floor), a textured one,
// one of ties and one whose lists outgrow their first room, at two sizes (one not a multiple of llvmpipe's 4x4
// blocks) and from two eyes.
TEST_F(InterpTest, OnePassFindsTheLayersThePeelFinds) {
  for (const auto& [file, fewest] :
       {std::pair<const char*, size_t>{"default.json", 3}, {"textured.json", 2}, {"ties", 2}, {"stack", 6}}) {
    const std::string name = file;
    const Scene scene = name == "ties"    ? coincidentPlanes()
                        : name == "stack" ? stackedPlanes()
                                          : loadScene(test::assetPath(file));
    for (const int size : {96, 173}) {
      ShearingCamera cam(*scene.camera, size, size * 3 / 4, 5);
      const double track = cam.spec().trackRight - cam.spec().trackLeft;
      RenderStats stats;
      for (const glm::dvec2 eye : {glm::dvec2(0.0), glm::dvec2(cam.viewX(0), 0.0)}) {
        const auto peeled =
            makeSourceLayerRenderer(scene, true, 1, Peeling::PassPerLayer)->render(cam, eye, 6, track, stats);
        const auto lists = makeSourceLayerRenderer(scene, true, 1, Peeling::OnePass)->render(cam, eye, 6, track, stats);
        ASSERT_GE(peeled.size(), fewest) << name;
        ASSERT_EQ(lists.size(), peeled.size()) << name;
        for (size_t k = 0; k < peeled.size(); ++k) {
          SCOPED_TRACE(name + ", layer " + std::to_string(k) + ", " + std::to_string(size) + " px");
          EXPECT_EQ(lists[k].depth, peeled[k].depth);
          EXPECT_EQ(lists[k].color.bytes, peeled[k].color.bytes);
          ASSERT_EQ(lists[k].normals.size(), peeled[k].normals.size());
          size_t normalsDiffer = 0;
          for (size_t i = 0; i < peeled[k].normals.size(); ++i)
            normalsDiffer += lists[k].normals[i] != peeled[k].normals[i];
          EXPECT_EQ(normalsDiffer, 0u);
        }
      }
    }
  }
}

// One pass of the mesh a source, a pass a layer where the lists would pass
// their memory limit: the same layers either way.
TEST_F(InterpTest, FragmentListsOverTheirLimitPeelAPassALayer) {
  const Scene scene = stackedPlanes();
  const ShearingCamera cam(*scene.camera, 96, 72, 5);
  const double track = cam.spec().trackRight - cam.spec().trackLeft;
  RenderStats lists, limited, peeled;
  const auto a = makeSourceLayerRenderer(scene)->render(cam, {0.0, 0.0}, 6, track, lists);
  FragmentLists::setMaxBytes(1024);  // the first room holds two fragments a pixel; ten would not fit
  const auto b = makeSourceLayerRenderer(scene)->render(cam, {0.0, 0.0}, 6, track, limited);
  FragmentLists::setMaxBytes(FragmentLists::kMaxBytes);
  const auto c = makeSourceLayerRenderer(scene, false, 1, Peeling::PassPerLayer)->render(cam, {0.0, 0.0}, 6, track, peeled);
  ASSERT_EQ(a.size(), 6u);
  ASSERT_EQ(b.size(), a.size());
  ASSERT_EQ(c.size(), a.size());
  EXPECT_EQ(lists.counters.at("layer_mesh_passes"), 1);
  EXPECT_EQ(limited.counters.at("layer_mesh_passes"), 6);
  EXPECT_EQ(peeled.counters.at("layer_mesh_passes"), 6);
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(b[k].depth, a[k].depth) << "layer " << k;
    EXPECT_EQ(b[k].color.bytes, a[k].color.bytes) << "layer " << k;
    EXPECT_EQ(c[k].depth, a[k].depth) << "layer " << k;
  }
}

TEST_F(InterpTest, SourceViewIsReproducedAndDualBeatsCenterAtTheEnds) {
  const Reference ref(5);
  const Scene& scene = ref.scene;
  const ShearingCamera& cam = ref.cam;
  const test::CaptureSink& reference = ref.views;
  auto center = makeInterpRenderer(scene, PixelType::U8, {Acquire::Center, 4, PstMode::Quad});
  auto dual = makeInterpRenderer(scene, PixelType::U8, {Acquire::Dual, 4, PstMode::Quad});
  RenderStats stats;
  const test::CaptureSink c = test::renderViews(*center, cam, stats);
  EXPECT_EQ(stats.counters["source_views"], 1);
  EXPECT_GE(stats.counters["layers"], 2);
  // The source view is the source's render, by another program than the
  // reference's: GL promises the same bits only to the same shader, so
  // within one 8-bit step (render_helpers.h; identical on llvmpipe, 97.4%
  // identical on an NVIDIA H100).
  EXPECT_LE(compareImages(reference.views.at({0, 2}), c.views.at({0, 2})).maxError, 1.0 / 255.0 + 1e-6);
  const test::CaptureSink d = test::renderViews(*dual, cam);
  for (int v = 0; v < 5; ++v) {
    const double pd = compareImages(reference.views.at({0, v}), d.views.at({0, v})).psnr;
    EXPECT_GE(pd, 24.0) << v;
    if (v == 0 || v == 4) {
      EXPECT_GT(pd, compareImages(reference.views.at({0, v}), c.views.at({0, v})).psnr) << v;
    }
  }
  // The CPU span rasterizer draws the same slices.
  auto cpu = makeInterpRenderer(scene, PixelType::U8, {Acquire::Dual, 4, PstMode::Cpu});
  EXPECT_GE(test::compareViews(d, test::renderViews(*cpu, cam)).minPsnr, 35.0);
}

// Issue 18: at a source view interp's image is the source's, within one
// 8-bit step, in every mode and from either path (GPU-sliced layers and
// layers read back), whatever the other sources' slices would draw there.
TEST_F(InterpTest, DualReproducesBothSourceViewsInEveryMode) {
  const Reference ref(5);
  for (PstMode mode : {PstMode::Quad, PstMode::Strip, PstMode::Exact, PstMode::Cpu})
    for (PstBuilder builder : {PstBuilder::Gpu, PstBuilder::Cpu}) {
      if (mode == PstMode::Cpu && builder == PstBuilder::Gpu) continue;
      const InterpOptions options{.acquire = Acquire::Dual, .mode = mode, .builder = builder};
      RenderStats stats;
      const test::CaptureSink d = test::renderViews(*makeInterpRenderer(ref.scene, PixelType::U8, options), ref.cam, stats);
      for (int v : {0, 4}) {
        const ImageDifference diff = compareImages(ref.views.views.at({0, v}), d.views.at({0, v}));
        EXPECT_LE(diff.maxError, 1.0 / 255.0 + 1e-6) << pstModeName(mode) << " " << stats.notes["image_slicer"] << " view " << v;
      }
      // Between the sources the slices are drawn, not a source.
      EXPECT_LT(compareImages(ref.views.views.at({0, 2}), d.views.at({0, 2})).identicalFraction, 1.0);
    }
}

TEST_F(InterpTest, EveryRowOfViewsReproducesItsOwnSourceView) {
  // Rows of views take turns with the EPI rasterizer, whose target is far
  // taller: each row's source views must still fill their own viewport.
  Scene scene = loadScene(test::assetPath("default.json"));
  CameraSpec spec = *scene.camera;
  spec.rowTop = 0.3, spec.rowBottom = -0.3;
  ShearingCamera cam(spec, 120, 90, 5, 2);
  const test::CaptureSink reference = test::renderViews(*makeDeferredRenderer(scene, PixelType::U8), cam);
  const test::CaptureSink c = test::renderViews(
      *makeInterpRenderer(scene, PixelType::U8, {.acquire = Acquire::Center}), cam);
  for (int row : {0, 1})  // within one 8-bit step, as above
    EXPECT_LE(compareImages(reference.views.at({row, 2}), c.views.at({row, 2})).maxError, 1.0 / 255.0 + 1e-6) << row;
}

TEST_F(InterpTest, CoalescingCutsSlicesAndKeepsTheSourceViewAndQuality) {
  const Reference ref(5);
  const Scene& scene = ref.scene;
  const ShearingCamera& cam = ref.cam;
  const test::CaptureSink& reference = ref.views;
  InterpOptions options{.acquire = Acquire::Center};
  RenderStats each, runs;
  auto plain = makeInterpRenderer(scene, PixelType::U8, options);
  const test::CaptureSink p = test::renderViews(*plain, cam, each);
  options.coalesce = 1.0f;
  auto coalesced = makeInterpRenderer(scene, PixelType::U8, options);
  const test::CaptureSink c = test::renderViews(*coalesced, cam, runs);
  EXPECT_EQ(runs.counters["slice_pixels"], each.counters["slice_pixels"]);
  EXPECT_LT(runs.counters["slices"], 0.5 * each.counters["slices"]);
  // The source view: every pixel read back at its own texel centre.
  EXPECT_GE(compareImages(reference.views.at({0, 2}), c.views.at({0, 2})).closeFraction, 0.999);
  for (int v : {0, 1, 3, 4}) {
    const double pc = compareImages(reference.views.at({0, v}), c.views.at({0, v})).psnr;
    EXPECT_GE(pc, compareImages(reference.views.at({0, v}), p.views.at({0, v})).psnr - 1.0) << v;
  }
  options.mode = PstMode::Cpu;
  auto cpu = makeInterpRenderer(scene, PixelType::U8, options);
  EXPECT_GE(test::compareViews(c, test::renderViews(*cpu, cam)).minPsnr, 35.0);
  options.mode = PstMode::Exact;
  auto exact = makeInterpRenderer(scene, PixelType::U8, options);
  EXPECT_GE(test::compareViews(c, test::renderViews(*exact, cam)).minPsnr, 35.0);
}

// Interp on the GPU (source layers kept in GPU memory, sliced by compute
// passes, PSTs pulled by the vertex shaders, vectors indexed per slice)
// draws what the CPU-sliced, CPU-built geometry draws: at least 99.9% of
// pixels identical, PSNR at least 45 dB, in every mode, with and without
// coalesced runs (vectors longer than a texel, with their MIP chains).
// The visibility filter and hierarchical acquisition's hole counts run as
// compute passes there too: the same layers, hidden pixels, hole checks
// and source views. The filter decides a pixel from the track's parallax
// in double precision, whose division GLSL promises no better than single
// (test::expectSameDecisions, tests/support/gl_fixture.h): off llvmpipe, with
// the filter on, hidden pixels and the slices they leave may differ by one
// in a thousand.
TEST_F(InterpTest, GpuSlicingAndPstsMatchTheCpuPath) {
  Scene scene = loadScene(test::assetPath("default.json"));
  const ShearingCamera small(*scene.camera, 96, 72, 7), large(*scene.camera, 120, 90, 9);
  struct Case {
    Acquire acquire;
    PstMode mode;
    float coalesce;
    bool visibility = false;
    int maxLayers = 4;  // hierarchical: fewer, and larger views, so that the ends leave holes
  };
  std::vector<Case> cases;
  for (PstMode mode : {PstMode::Quad, PstMode::Strip, PstMode::Exact})
    for (float coalesce : {0.0f, 1.0f}) cases.push_back({Acquire::Dual, mode, coalesce});
  cases.push_back({Acquire::Center, PstMode::Quad, 1.0f});
  cases.push_back({Acquire::Center, PstMode::Quad, 0.0f, true});
  cases.push_back({Acquire::Dual, PstMode::Strip, 1.0f, true});
  cases.push_back({Acquire::Hierarchical, PstMode::Quad, 0.0f, false, 1});
  cases.push_back({Acquire::Hierarchical, PstMode::Strip, 1.0f, true, 2});
  for (const Case& c : cases) {
    InterpOptions options{.acquire = c.acquire, .maxLayers = c.maxLayers, .mode = c.mode, .coalesce = c.coalesce,
                          .visibility = c.visibility};
    const ShearingCamera& cam = c.acquire == Acquire::Hierarchical ? large : small;
    options.holeFraction = 0.0;  // hierarchical: a source wherever a hole is left
    options.builder = PstBuilder::Gpu;
    RenderStats gpuStats, cpuStats;
    const auto gpu = test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam, gpuStats);
    options.builder = PstBuilder::Cpu;
    const auto cpu = test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam, cpuStats);
    const std::string label = std::string(acquireName(c.acquire)) + " " + pstModeName(c.mode) + " coalesce " +
                              std::to_string(c.coalesce) + (c.visibility ? " visibility" : "");
    EXPECT_EQ(gpuStats.notes["pst_builder"], "gpu") << label;
    EXPECT_EQ(cpuStats.notes["pst_builder"], "cpu") << label;
    EXPECT_EQ(gpuStats.notes["image_slicer"], "gpu") << label;
    EXPECT_EQ(cpuStats.notes["image_slicer"], "cpu") << label;
    for (const char* counter : {"slices", "slice_pixels", "hidden_pixels"}) {
      const long got = long(gpuStats.counters[counter]), want = long(cpuStats.counters[counter]);
      if (c.visibility)
        test::expectSameDecisions(got, want, want, label + " " + counter);
      else
        EXPECT_EQ(got, want) << label << " " << counter;
    }
    EXPECT_EQ(gpuStats.counters["layers"], cpuStats.counters["layers"]) << label;
    EXPECT_EQ(gpuStats.counters["hole_checks"], cpuStats.counters["hole_checks"]) << label;
    EXPECT_EQ(gpuStats.counters["source_views"], cpuStats.counters["source_views"]) << label;
    if (c.acquire == Acquire::Hierarchical) {
      EXPECT_GT(gpuStats.counters["source_views"], 2) << label;
    }
    if (c.visibility) {
      EXPECT_GT(gpuStats.counters["hidden_pixels"], 0) << label;
    }
    const auto d = test::compareViews(cpu, gpu);
    EXPECT_GE(d.minIdentical, 0.999) << label;
    EXPECT_GE(d.minPsnr, 45.0) << label;
  }
}

long totalHoles(const test::CaptureSink& reference, const test::CaptureSink& b) {
  long holes = 0;
  for (const auto& [key, img] : reference.views) holes += compareImages(img, b.views.at(key)).holes;
  return holes;
}

TEST_F(InterpTest, HierarchicalAddsSourcesWhereTheEndsLeaveHoles) {
  const Reference ref(9);
  const Scene& scene = ref.scene;
  const ShearingCamera& cam = ref.cam;
  const test::CaptureSink& reference = ref.views;
  // One layer per source: the ends alone cannot see behind the cup's rim.
  InterpOptions options{.acquire = Acquire::Dual, .maxLayers = 1};
  const test::CaptureSink dual = test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam);
  options.acquire = Acquire::Hierarchical;
  RenderStats stats;
  const test::CaptureSink h = test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam, stats);
  EXPECT_GT(stats.counters["source_views"], 2);
  EXPECT_LE(stats.counters["source_views"], options.budget);
  EXPECT_GE(stats.counters["hole_checks"], 1);
  EXPECT_LT(totalHoles(reference, h), totalHoles(reference, dual));
  // A budget of two is dual.
  options.budget = 2;
  const test::CaptureSink two = test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam);
  EXPECT_EQ(test::compareViews(dual, two).minIdentical, 1.0);
}

// Intervals (more than two sources) and blending in a split job: each
// share's EPIs are the whole render's, byte for byte.
TEST_F(InterpTest, IntervalsAndBlendingJoinAcrossShares) {
  const Scene scene = loadScene(test::assetPath("default.json"));
  const ShearingCamera cam(*scene.camera, 48, 37, 9);
  const InterpOptions options{
      .acquire = Acquire::Hierarchical, .budget = 4, .blend = Blend::Track, .holeFraction = -1.0};
  auto renderer = makeInterpRenderer(scene, PixelType::U8, options);
  test::CaptureSink whole;
  RenderStats stats;
  renderer->render(cam, whole, stats);
  EXPECT_EQ(stats.counters["source_views"], 4);
  for (IndexRange part : {IndexRange{0, 5}, IndexRange{5, 37}}) {
    RenderShare share = cam.share();
    share.scanlines = part;
    test::CaptureSink got;
    renderer->render(cam.withShare(share), got, stats);
    EXPECT_EQ(got.epis.size(), size_t(part.size()));
    for (const auto& [key, epi] : got.epis) EXPECT_EQ(epi.bytes, whole.epis.at(key).bytes) << "scanline " << key.second;
  }
}

TEST_F(InterpTest, VisibilityDropsHiddenPixelsWithoutOpeningHoles) {
  const Reference ref(5);
  const Scene& scene = ref.scene;
  const ShearingCamera& cam = ref.cam;
  const test::CaptureSink& reference = ref.views;
  InterpOptions options{.acquire = Acquire::Center};
  RenderStats all, visible;
  const test::CaptureSink a = test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam, all);
  options.visibility = true;
  const test::CaptureSink v = test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam, visible);
  EXPECT_GT(visible.counters["hidden_pixels"], 0);
  EXPECT_LT(visible.counters["slices"], all.counters["slices"]);
  EXPECT_LE(totalHoles(reference, v), totalHoles(reference, a));
  EXPECT_GE(test::compareViews(a, v).minPsnr, 40.0);
}

// A specular plane on the image plane under a point light: nothing moves
// between views but the highlight, so every difference from deferred is
// the highlight's.
Scene specularPlane() {
  const std::string path = ::testing::TempDir() + "/mvr_specular_plane.json";
  std::ofstream(path) << R"({"meshes": [{"file": ")" << test::assetPath("plane.obj") << R"(",
    "material": {"diffuse": [0.3, 0.35, 0.4], "specular": [0.8, 0.8, 0.8], "shininess": 30,
                 "specular_model": "phong"}}],
    "lights": [{"type": "point", "position": [0.2, 0.1, 1.2], "color": [1, 1, 1]}],
    "ambient": [0.1, 0.1, 0.1],
    "camera": {"distance": 3.0, "image_plane": 0.8, "track": [-1, 1], "near": 2.0, "far": 4.0}})";
  return loadScene(path);
}

TEST_F(InterpTest, SplitTracksMoveHighlightsWithTheView) {
  Scene scene = specularPlane();
  ShearingCamera cam(*scene.camera, 96, 72, 9);
  const test::CaptureSink reference = test::renderViews(*makeDeferredRenderer(scene, PixelType::U8), cam);
  InterpOptions options{.acquire = Acquire::Center};
  auto worst = [&](const test::CaptureSink& c) {
    double maxError = 0;
    for (const auto& [key, img] : reference.views)
      maxError = std::max(maxError, compareImages(img, c.views.at(key)).maxError);
    return maxError;
  };
  const double baked = worst(test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam));
  // K pairs of splits: the highlight is off by about 1/(K + 1) of its
  // peak (0.8) at most.
  options.splits = 3;
  RenderStats stats;
  const test::CaptureSink split = test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam, stats);
  EXPECT_GT(stats.counters["highlight_knots"], 2 * stats.counters["slices"]);
  EXPECT_GT(baked, 0.5);  // the baked highlight stays where the centre saw it
  EXPECT_LT(worst(split), 0.2);
  options.mode = PstMode::Cpu;
  EXPECT_GE(test::compareViews(split, test::renderViews(*makeInterpRenderer(scene, PixelType::U8, options), cam))
                .minPsnr, 40.0);
  // A diffuse scene has no highlight to split: the same images as K = 0.
  Scene diffuse = loadScene(test::assetPath("default.json"));
  ShearingCamera small(*diffuse.camera, 60, 45, 3);
  RenderStats none;
  const test::CaptureSink d3 = test::renderViews(
      *makeInterpRenderer(diffuse, PixelType::U8, {.acquire = Acquire::Center, .splits = 3}), small, none);
  const test::CaptureSink d0 =
      test::renderViews(*makeInterpRenderer(diffuse, PixelType::U8, {.acquire = Acquire::Center}), small);
  EXPECT_EQ(test::compareViews(d0, d3).minIdentical, 1.0);
  EXPECT_EQ(none.counters.count("highlight_knots"), 0u);
}

// Slicing runs in bands of scanlines on the pool; joined, every slot of
// the table holds the slice a single pass makes: the same ends, vector,
// texels and highlight knots (default scene beside a specular plane, split
// tracks and coalescing on, so every part of a slice is exercised).
TEST_F(InterpTest, SlicingInBandsJoinsToTheSingleBandTable) {
  Scene scene = specularPlane();
  const ShearingCamera cam(*scene.camera, 72, 45, 9);
  auto sources = makeSourceLayerRenderer(scene, true);
  RenderStats stats;
  const double track = cam.spec().trackRight - cam.spec().trackLeft;
  std::vector<SourceLayer> layers;
  for (double x : {cam.viewX(0), cam.viewX(8)})
    for (SourceLayer& l : sources->render(cam, {x, 0.0}, 4, track, stats)) layers.push_back(std::move(l));
  ImageSliceOptions options{.overlap = 0.25f, .coalesce = 0.5f, .scene = &scene, .splits = 2,
                            .bandRows = cam.height()};
  const ImageSlices whole = sliceSourceLayers(layers, cam, 0, options);
  ASSERT_GT(whole.vertices.knots.size(), 0u);
  for (int bandRows : {1, 7}) {
    options.bandRows = bandRows;
    const ImageSlices banded = sliceSourceLayers(layers, cam, 0, options);
    ASSERT_TRUE(std::ranges::equal(banded.table.offsets(), whole.table.offsets())) << bandRows;
    EXPECT_EQ(banded.pixels, whole.pixels);
    const auto& wv = whole.vertices;
    const auto& bv = banded.vertices;
    for (size_t s = 0; s < whole.table.sliceCount(); ++s) {
      const uint32_t a = whole.table.slices()[s].triangle, b = banded.table.slices()[s].triangle;
      for (int end = 0; end < 2; ++end) {
        const uint32_t p = wv.triangles[a][end], q = bv.triangles[b][end];
        ASSERT_EQ(wv.x0[p], bv.x0[q]) << bandRows << " slot " << s;
        ASSERT_EQ(wv.y[p], bv.y[q]);
        ASSERT_EQ(wv.depth[p], bv.depth[q]);
        ASSERT_EQ(wv.frontOverW[p], bv.frontOverW[q]);
      }
      const SliceVector &x = wv.vectors[a], &y = bv.vectors[b];
      ASSERT_EQ(x.length, y.length);
      ASSERT_EQ(x.u0, y.u0);
      ASSERT_EQ(x.knotCount, y.knotCount);
      for (int t = 0; t < 2 * x.length - 1; ++t)
        ASSERT_EQ(wv.vectorTexels.texels()[x.base + t], bv.vectorTexels.texels()[y.base + t]);
      for (int k = 0; k < x.knotCount; ++k) {
        ASSERT_EQ(wv.knots[x.firstKnot + k].r, bv.knots[y.firstKnot + k].r);
        ASSERT_EQ(wv.knots[x.firstKnot + k].specular, bv.knots[y.firstKnot + k].specular);
      }
    }
  }
}

TEST_F(InterpTest, OneViewAndBadOptions) {
  Scene scene = loadScene(test::assetPath("default.json"));
  ShearingCamera one(*scene.camera, 40, 30, 1);
  auto dual = makeInterpRenderer(scene, PixelType::U8, {Acquire::Dual, 2, PstMode::Quad});
  RenderStats stats;
  const test::CaptureSink v = test::renderViews(*dual, one, stats);
  EXPECT_EQ(v.views.size(), 1u);
  EXPECT_EQ(stats.counters["source_views"], 1);  // both ends are the one view
  EXPECT_THROW(makeInterpRenderer(scene, PixelType::U8, {Acquire::Dual, 0, PstMode::Quad}), Error);
  EXPECT_THROW(parseAcquire("hierarchical-ish"), Error);
  EXPECT_THROW(makeInterpRenderer(scene, PixelType::U8, {.coalesce = -1.0f}), Error);
  EXPECT_THROW(makeInterpRenderer(scene, PixelType::U8, {.budget = 1}), Error);
  EXPECT_THROW(makeInterpRenderer(scene, PixelType::U8, {.outlineSamples = 0}), Error);
  EXPECT_THROW(makeInterpRenderer(scene, PixelType::U8, {.outlineSamples = 17}), Error);
  EXPECT_THROW(makeInterpRenderer(scene, PixelType::U8, {.splits = -1}), Error);
}

// How far outside the true silhouette a covered pixel's centre lies, along
// its scanline: 0 where the reference covers the centre, else the distance
// to the nearest covered sample of a reference `factor` times finer in x
// (samples at (i + 0.5) / factor), in pixels; infinity when none is on the row.
double outsideDistance(const Image& fine, int factor, int x, int y) {
  const double centre = x + 0.5;
  double best = INFINITY;
  for (int i = 0; i < fine.width; ++i)
    if (fine.row(y)[i * 4 + 3] != 0) best = std::min(best, std::abs((i + 0.5) / factor - centre));
  return best;
}

// The worst distance, over every view, of an interp pixel's centre outside
// the true silhouette, and how many lie more than half a pixel out, against
// svr 16 times finer in x.
struct Outside {
  double worst = 0.0;
  long beyondHalf = 0;
};
Outside outsideTheSilhouette(const Scene& scene, const ShearingCamera& cam, Acquire acquire) {
  constexpr int kFactor = 16;
  CameraSpec fineSpec = cam.spec();
  fineSpec.planeHeight = cam.planeHeight();
  const ShearingCamera fine(fineSpec, cam.width() * kFactor, cam.height(), cam.views());
  const test::CaptureSink reference = test::renderViews(*makeSvrRenderer(scene, PixelType::U8), fine);
  const test::CaptureSink got =
      test::renderViews(*makeInterpRenderer(scene, PixelType::U8, {.acquire = acquire, .mode = PstMode::Cpu}), cam);
  Outside out;
  for (const auto& [key, img] : got.views)
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        if (img.row(y)[x * 4 + 3] == 0) continue;
        const double d = outsideDistance(reference.views.at(key), kFactor, x, y);
        out.worst = std::max(out.worst, d);
        out.beyondHalf += d > 0.5 + 0.5 / kFactor;
      }
  return out;
}

// The finer outline (issue 18): at 4 samples a pixel, a silhouette
// pixel's outline end lies within half a sample of the true silhouette
// (svr 16 times finer in x, through the source's own eye), within its
// pixel or over the empty neighbour's near half.
TEST_F(InterpTest, TheFinerOutlineFindsTheSilhouetteWithinHalfASample) {
  const Scene sphere = test::sphereScene(0.6f, 48, 96);
  const ShearingCamera cam(cameraFor(sphere, 80, 60), 80, 60, 9);
  constexpr int kFactor = 16;
  CameraSpec fineSpec = cam.spec();
  fineSpec.planeHeight = cam.planeHeight();
  const ShearingCamera fine(fineSpec, cam.width() * kFactor, cam.height(), cam.views());
  const test::CaptureSink reference = test::renderViews(*makeSvrRenderer(sphere, PixelType::U8), fine);
  const Image& truth = reference.views.at({0, 0});
  RenderStats stats;
  const double track = cam.spec().trackRight - cam.spec().trackLeft;
  const std::vector<SourceLayer> layers =
      makeSourceLayerRenderer(sphere, false, 4)->render(cam, {cam.viewX(0), cam.rowY(0)}, 1, track, stats);
  ASSERT_EQ(layers.size(), 1u);
  const SourceLayer& front = layers[0];
  int rows = 0, beyond = 0;
  for (int y = 0; y < cam.height(); ++y) {
    const float* depth = front.depth.data() + size_t(y) * cam.width();
    int first = 0, last = cam.width() - 1;
    while (first < cam.width() && depth[first] == 0.0f) ++first;
    while (last >= 0 && depth[last] == 0.0f) --last;
    int c0 = 0, c1 = truth.width - 1;
    while (c0 < truth.width && truth.row(y)[c0 * 4 + 3] == 0) ++c0;
    while (c1 >= 0 && truth.row(y)[c1 * 4 + 3] == 0) --c1;
    if (last - first < 2 || c1 - c0 < 2 * kFactor) continue;
    ++rows;
    const PixelOutline& l = front.outline[size_t(y) * cam.width() + first];
    const PixelOutline& r = front.outline[size_t(y) * cam.width() + last];
    // The true edges, between a covered fine sample and the next one out.
    EXPECT_NEAR(first + l.left, double(c0) / kFactor, 0.125 + 0.5 / kFactor) << "row " << y;
    EXPECT_NEAR(last + r.right, double(c1 + 1) / kFactor, 0.125 + 0.5 / kFactor) << "row " << y;
    EXPECT_GE(l.left, -0.5f);
    EXPECT_LE(r.right, 1.5f);
    beyond += (l.left < 0.0f) + (r.right > 1.0f);
  }
  EXPECT_GT(rows, 30);
  EXPECT_GT(beyond, 10);  // ends over the empty neighbour: about half of them
}

// Issue 18: no interp pixel more than half a pixel outside the true
// silhouette, on a cube, a sphere and thin bars before a deep box.
TEST_F(InterpTest, NoPixelMoreThanHalfAPixelOutsideTheSilhouette) {
  const Scene cube = loadScene(test::assetPath("cube.json"));
  const Scene sphere = test::sphereScene(0.6f, 48, 96);
  const Scene thin = app::makeThinAndDeepScene();
  const std::pair<const char*, const Scene*> scenes[] = {{"cube", &cube}, {"sphere", &sphere}, {"thin-deep", &thin}};
  for (const auto& [name, scene] : scenes) {
    const ShearingCamera cam(scene->camera ? *scene->camera : cameraFor(*scene, 80, 60), 80, 60, 9);
    for (Acquire acquire : {Acquire::Dual, Acquire::Hierarchical}) {
      const Outside o = outsideTheSilhouette(*scene, cam, acquire);
      EXPECT_EQ(o.beyondHalf, 0) << name << " " << int(acquire) << ": worst " << o.worst;
      RecordProperty(std::string(name) + "_worst_outside_px", std::to_string(o.worst));
    }
  }
}

// Scenes interp was not tuned on (issue 18). The scanned bunny comes from
// Debian's glmark2-data (GPL, not in the repo): skipped where absent.
// Thresholds are today's figures less a margin. These are linear 8-bit
// images; issue 18's target (32 dB on the bunny at 160x120) is measured on
// what mvr render writes, sRGB-encoded, where the same views score lower
// (31.2 dB) and the target is not met: docs/BENCHMARKS.md.
TEST_F(InterpTest, ScenesItWasNotTunedOn) {
  struct Case {
    const char* name;
    Scene scene;
    double minPsnr;
    double halvesGain;   // dB drawing each half from its near source's layers adds at least
    double outlineGain;  // dB the sources' finer outlines add at least
    double blendGain;    // dB blending adds at least (negative: loses at most)
  };
  std::vector<Case> cases;
  // Bars thinner than a pixel: svr drops or keeps them by where pixel
  // centres fall, so an image-based view differs from it whole bars at a
  // time. Measured (llvmpipe): thin-deep 16.3 dB, 15.9 with outlines at the
  // pixels' boundaries, 16.2 over the whole track, blending 16.7-16.8;
  // bunny 33.8 dB (31.7 before the outlines ran over the empty neighbour,
  // joined pixels shared their ends and the layers behind were inset),
  // 33.0 with all layers over the whole track, 31.2 with outlines at the
  // pixels' boundaries, blending (whole track) 33.6.
  cases.push_back({"thin-deep", app::makeThinAndDeepScene(), 16.0, -0.1, 0.3, 0.2});
  const char* bunny = "/usr/share/glmark2/models/bunny.obj";
  if (std::filesystem::exists(bunny)) cases.push_back({"bunny", app::loadInputScene(bunny, false), 33.3, 0.5, 1.3, -0.6});
  for (const Case& c : cases) {
    const ShearingCamera cam(cameraFor(c.scene, 160, 120), 160, 120, 16);
    const test::CaptureSink svr = test::renderViews(*makeSvrRenderer(c.scene, PixelType::U8), cam);
    const test::CaptureSink dual = test::renderViews(*makeInterpRenderer(c.scene, PixelType::U8, {}), cam);
    const test::SetDifference d = test::compareViews(svr, dual);
    EXPECT_GE(d.minPsnr, c.minPsnr) << c.name;
    RecordProperty(std::string(c.name) + "_dual_min_psnr_db", std::to_string(d.minPsnr));
    const test::CaptureSink whole = test::renderViews(*makeInterpRenderer(c.scene, PixelType::U8, {.halves = false}), cam);
    const double wholePsnr = test::compareViews(svr, whole).minPsnr;
    RecordProperty(std::string(c.name) + "_whole_min_psnr_db", std::to_string(wholePsnr));
    EXPECT_GE(d.minPsnr, wholePsnr + c.halvesGain) << c.name;
    // Silhouette slices end where the surface does within their pixels.
    const test::CaptureSink coarse =
        test::renderViews(*makeInterpRenderer(c.scene, PixelType::U8, {.outlineSamples = 1}), cam);
    const double coarsePsnr = test::compareViews(svr, coarse).minPsnr;
    RecordProperty(std::string(c.name) + "_coarse_min_psnr_db", std::to_string(coarsePsnr));
    EXPECT_GE(d.minPsnr, coarsePsnr + c.outlineGain) << c.name;
    // At a source view nothing is drawn where the source saw nothing.
    for (int v : {0, 15}) EXPECT_EQ(compareImages(svr.views.at({0, v}), dual.views.at({0, v})).extras, 0) << c.name << " " << v;
    // Blending weights the two outlines' disagreement and mixes one
    // surface seen twice, with rims fitted where no finer outline is; on
    // the bunny it now trails the halves it cannot use.
    for (Blend blend : {Blend::Track, Blend::Angular}) {
      const InterpOptions options{.blend = blend};
      const test::CaptureSink b = test::renderViews(*makeInterpRenderer(c.scene, PixelType::U8, options), cam);
      const test::SetDifference bd = test::compareViews(svr, b);
      RecordProperty(std::string(c.name) + "_" + nameOf(kBlendNames, blend) + "_min_psnr_db", std::to_string(bd.minPsnr));
      EXPECT_GE(bd.minPsnr, d.minPsnr + c.blendGain) << c.name << " " << nameOf(kBlendNames, blend);
      for (int v : {0, 15}) {
        EXPECT_LE(compareImages(dual.views.at({0, v}), b.views.at({0, v})).maxError, 1e-6) << c.name << " " << v;
      }
    }
    // More sources, each interval from its own two: no worse than dual
    // (across the whole track, 9 sources on the bunny scored 18.6 dB).
    InterpOptions many{.acquire = Acquire::Hierarchical, .budget = 5, .holeFraction = -1.0};
    RenderStats stats;
    const test::CaptureSink h = test::renderViews(*makeInterpRenderer(c.scene, PixelType::U8, many), cam, stats);
    EXPECT_EQ(stats.counters["source_views"], 5) << c.name;
    const double hPsnr = test::compareViews(svr, h).minPsnr;
    RecordProperty(std::string(c.name) + "_five_sources_min_psnr_db", std::to_string(hPsnr));
    EXPECT_GE(hPsnr, d.minPsnr - 0.3) << c.name;
  }
  if (cases.size() < 2) GTEST_SKIP() << bunny << " absent (Debian's glmark2-data)";
}

}  // namespace
}  // namespace mvr
