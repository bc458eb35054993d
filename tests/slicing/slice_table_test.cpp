#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <random>
#include <vector>

#include "mvr/assets/scene_io.h"
#include "shading/lighting.h"
#include "slicing/extreme_vertices.h"
#include "slicing/gpu/gpu_slicer.h"
#include "slicing/slice_table.h"
#include "tests/support/gl_fixture.h"
#include "tests/support/meshes.h"

namespace mvr {
namespace {

// Random triangles straight in extreme-vertex form (pixel units).
ExtremeVertices randomTriangles(int count, int height, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> y(-20.0f, height + 20.0f), x(-50.0f, 150.0f),
      d(-3.0f, 3.0f), z(0.05f, 0.95f);
  ExtremeVertices v;
  for (int i = 0; i < 3 * count; ++i) {
    v.x0.push_back(x(rng));
    v.dx.push_back(d(rng));
    v.y.push_back(i % 7 == 0 ? std::round(y(rng)) + 0.5f : y(rng));  // some on centres
    v.depth.push_back(z(rng));
    v.invW.push_back(1.0f);
    v.frontOverW.emplace_back(1.0f);
    v.backOverW.emplace_back(0.5f);
  }
  for (int t = 0; t < count; ++t) {
    v.triangles.push_back(glm::uvec3(3 * t, 3 * t + 1, 3 * t + 2));
    v.cullBack.push_back(0);
  }
  return v;
}

TEST(SliceTable, CountsMatchBruteForce) {
  const int height = 60;
  ExtremeVertices v = randomTriangles(500, height, 7);
  SliceTable table = SliceTable::build(v, height, 2);
  size_t expected = 0;
  std::vector<size_t> perLine(height, 0);
  for (const glm::uvec3& t : v.triangles) {
    const float lo = std::min({v.y[t.x], v.y[t.y], v.y[t.z]});
    const float hi = std::max({v.y[t.x], v.y[t.y], v.y[t.z]});
    for (int j = 0; j < height; ++j)
      if (lo <= j + 0.5f && j + 0.5f < hi) ++expected, ++perLine[j];
  }
  EXPECT_EQ(table.sliceCount(), expected);
  for (int j = 0; j < height; ++j) EXPECT_EQ(table.scanline(j).size(), perLine[j]) << j;
}

TEST(SliceTable, EndpointsLieOnTriangleEdgesAtScanlineCentres) {
  const int height = 40;
  ExtremeVertices v = randomTriangles(300, height, 11);
  SliceTable table = SliceTable::build(v, height, 2);
  ASSERT_GT(table.sliceCount(), 100u);
  for (int j = 0; j < height; ++j) {
    const float yc = j + 0.5f;
    for (const Slice& s : table.scanline(j)) {
      const glm::uvec3 t = v.triangles[s.triangle];
      auto [e0, e1] = sliceEnds(v, s);
      for (const SliceEnd& e : {e0, e1}) {
        bool onEdge = false;
        for (int k = 0; k < 3; ++k) {
          const uint32_t p = t[k], q = t[(k + 1) % 3];
          const float lo = std::min(v.y[p], v.y[q]), hi = std::max(v.y[p], v.y[q]);
          if (yc < lo || yc > hi || lo == hi) continue;
          const float f = (yc - v.y[p]) / (v.y[q] - v.y[p]);
          const float x = v.x0[p] + f * (v.x0[q] - v.x0[p]);
          const float dx = v.dx[p] + f * (v.dx[q] - v.dx[p]);
          if (std::abs(x - e.x0) < 1e-3f && std::abs(dx - e.dx) < 1e-4f) onEdge = true;
        }
        EXPECT_TRUE(onEdge) << "scanline " << j << " triangle " << s.triangle;
      }
    }
  }
}

TEST(SliceTable, ThreadCountDoesNotChangeTheTable) {
  ExtremeVertices v = randomTriangles(400, 50, 3);
  SliceTable one = SliceTable::build(v, 50, 1), two = SliceTable::build(v, 50, 2),
             many = SliceTable::build(v, 50, 7);
  ASSERT_EQ(one.sliceCount(), two.sliceCount());
  ASSERT_EQ(one.sliceCount(), many.sliceCount());
  for (int j = 0; j < 50; ++j)
    for (size_t k = 0; k < one.scanline(j).size(); ++k) {
      EXPECT_EQ(one.scanline(j)[k].triangle, two.scanline(j)[k].triangle);
      EXPECT_EQ(one.scanline(j)[k].triangle, many.scanline(j)[k].triangle);
      EXPECT_EQ(one.scanline(j)[k].tLong, many.scanline(j)[k].tLong);
    }
}

TEST(SliceTable, NoSliceOutsideTheImage) {
  ExtremeVertices v = randomTriangles(200, 30, 5);
  SliceTable table = SliceTable::build(v, 30, 2);
  EXPECT_EQ(table.height(), 30);
  size_t sum = 0;
  for (int j = 0; j < 30; ++j) sum += table.scanline(j).size();
  EXPECT_EQ(sum, table.sliceCount());
  EXPECT_EQ(scanlineRange(-10.0f, -5.0f, -1.0f, 30), std::make_pair(0, 0));
  EXPECT_EQ(scanlineRange(31.0f, 40.0f, 35.0f, 30).first, scanlineRange(31.0f, 40.0f, 35.0f, 30).second);
  EXPECT_EQ(scanlineRange(1.5f, 3.5f, 2.0f, 30), std::make_pair(1, 3));  // centres 1.5, 2.5
}

// Facing: x1 - x0 > 0 exactly where the triangle faces the camera.
TEST(SliceTable, EndpointOrderFollowsFacing) {
  ShearingCamera cam(CameraSpec{}, 100, 100, 5);
  Scene s;
  // Counter-clockwise seen from +z (the camera side): front facing.
  s.positions = {{-0.5f, -0.5f, 0.0f}, {0.5f, -0.5f, 0.0f}, {0.0f, 0.5f, 0.0f},
                 {-0.5f, -0.5f, 0.1f}, {0.0f, 0.5f, 0.1f}, {0.5f, -0.5f, 0.1f}};
  s.normals.assign(6, glm::vec3(0, 0, 1));
  s.colors.assign(6, glm::vec3(1));
  s.triangles = {{0, 1, 2}, {3, 4, 5}};
  s.materialIds = {0, 0};
  s.materials.emplace_back();
  ExtremeVertices v = transformToExtremes(s, shading::litVertexColors(s), cam, 0);
  SliceTable table = SliceTable::build(v, 100, 1);
  for (const Slice& sl : table.scanline(50)) {
    auto [e0, e1] = sliceEnds(v, sl);
    if (sl.triangle == 0) {
      EXPECT_GT(e1.x0 - e0.x0, 0.0f);
    }
    else EXPECT_LT(e1.x0 - e0.x0, 0.0f);
  }
  EXPECT_EQ(table.scanline(50).size(), 2u);
}

TEST(ExtremeVertices, ImagePlaneHasZeroDisparityAndDepthHasTheClosedForm) {
  CameraSpec spec;  // D 4, plane 2 wide, track -1..1
  ShearingCamera cam(spec, 100, 100, 11);
  Scene s;
  s.positions = {{0.2f, 0.1f, 0.0f}, {0.2f, 0.1f, -2.0f}, {0.3f, 0.4f, 1.0f}};
  s.normals.assign(3, glm::vec3(0, 0, 1));
  s.colors.assign(3, glm::vec3(1));
  s.triangles = {{0, 1, 2}};
  s.materialIds = {0};
  s.materials.emplace_back();
  ExtremeVertices v = transformToExtremes(s, shading::litVertexColors(s), cam, 0);
  EXPECT_FLOAT_EQ(v.dx[0], 0.0f);
  EXPECT_NEAR(v.x0[0], 60.0f, 1e-4);
  // Per view: -(W / Wp) z / (D - z) * spacing = -(50)(-2)/6 * 0.2
  EXPECT_NEAR(v.dx[1], 50.0 * 2.0 / 6.0 * 0.2, 1e-5);
  for (int i = 0; i < 11; ++i)
    EXPECT_NEAR(v.x0[2] + i * v.dx[2], cam.project(glm::dvec3(s.positions[2]), i).x, 1e-4);
}

}  // namespace
}  // namespace mvr

namespace mvr {
namespace {

// The GPU slicer against the CPU slicer (the oracle): the same offsets,
// per scanline the same triangles in the same order with the same corner
// flags, and endpoints within 1e-4 px in every view (x at r = 0 and r = N
// for N = 100) plus what the edge parameter's rounding moves them: both
// slicers divide t = (yc - ya) / (yb - ya) in float, GLSL lets the GPU's
// division err by 2.5 ulp where the CPU's rounds correctly, and each
// subtraction rounds by half an ulp, so t may differ by 4 ulp (relative);
// an end x = xa + t (xb - xa) then moves by 4 eps t |xb - xa|, which on
// random triangles spanning 900 px at r = 100 is 4e-4 px (NVIDIA H100:
// 1.07e-4 px seen at x = -103.7).
// With a band, both slicers are given it; without, both slice every scanline.
// 4 eps t |xb - xa| at view r for each end of a slice: how far a 4-ulp
// difference in its edge parameter moves it (0 for a segment's ends).
std::pair<float, float> edgeMotion(const ExtremeVertices& v, const Slice& s, float r) {
  if (s.flags & kSegmentSlice) return {0.0f, 0.0f};
  const glm::uvec3 t = v.triangles[s.triangle];
  const uint32_t a = t[s.flags & 3], b = t[(s.flags >> 2) & 3], c = t[(s.flags >> 4) & 3];
  auto x = [&](uint32_t i) { return v.x0[i] + (r - 0.5f) * v.dx[i]; };
  constexpr float k4Ulp = 4.0f * std::numeric_limits<float>::epsilon();
  const float onLong = k4Ulp * std::abs(s.tLong * (x(c) - x(a)));
  const float onShort = k4Ulp * std::abs(s.tShort * ((s.flags & (1u << 6)) ? x(c) - x(b) : x(b) - x(a)));
  return (s.flags & (1u << 7)) ? std::pair{onShort, onLong} : std::pair{onLong, onShort};
}

void expectSameTable(const ExtremeVertices& v, int height, const char* label,
                     std::optional<IndexRange> band = std::nullopt) {
  const SliceTable cpu = band ? SliceTable::build(v, height, *band) : SliceTable::build(v, height);
  GpuSlicer slicer;
  const GpuSliceTable device = band ? slicer.build(v, height, *band) : slicer.build(v, height);
  EXPECT_EQ(device.offsets(), std::vector<uint32_t>(cpu.offsets().begin(), cpu.offsets().end())) << label;
  const SliceTable gpu = device.download();
  ASSERT_EQ(gpu.sliceCount(), cpu.sliceCount()) << label;
  for (int j = 0; j < height; ++j) {
    const auto a = cpu.scanline(j), b = gpu.scanline(j);
    ASSERT_EQ(a.size(), b.size()) << label << " scanline " << j;
    for (size_t k = 0; k < a.size(); ++k) {
      ASSERT_EQ(a[k].triangle, b[k].triangle) << label << " scanline " << j;
      ASSERT_EQ(a[k].flags, b[k].flags) << label << " scanline " << j;
      const auto [a0, a1] = sliceEnds(v, a[k]);
      const auto [b0, b1] = sliceEnds(v, b[k]);
      for (float r : {0.0f, 100.0f}) {
        auto x = [r](const SliceEnd& e) { return e.x0 + (r - 0.5f) * e.dx; };
        const auto [m0, m1] = edgeMotion(v, a[k], r);
        auto tolerance = [&](float at, float motion) {
          return 1e-4f * std::max(1.0f, std::abs(at) / 100.0f) + motion;
        };
        ASSERT_NEAR(x(a0), x(b0), tolerance(x(a0), m0)) << label << " scanline " << j;
        ASSERT_NEAR(x(a1), x(b1), tolerance(x(a1), m1)) << label << " scanline " << j;
      }
    }
  }
}

TEST(GpuSlicer, MatchesTheCpuSlicerOnRandomTriangles) {
  test::sharedContext();
  expectSameTable(randomTriangles(3000, 60, 5), 60, "random");
  expectSameTable(randomTriangles(7, 1, 9), 1, "one scanline");
}

TEST(GpuSlicer, MatchesTheCpuSlicerOnTheTeacup) {
  test::sharedContext();
  const Scene scene = loadScene(test::assetPath("default.json"));
  const ShearingCamera cam(cameraFor(scene, 120, 90), 120, 90, 8);
  expectSameTable(transformToExtremes(scene, shading::litVertexColors(scene), cam, 0), 90, "teacup");
}

// A split job's band: the scanlines outside it get no slices, as from the
// CPU slicer given the same band.
TEST(GpuSlicer, SlicesOnlyABandWhenAskedAsTheCpuSlicerDoes) {
  test::sharedContext();
  const ExtremeVertices v = randomTriangles(2000, 60, 11);
  expectSameTable(v, 60, "band", IndexRange{17, 41});
  expectSameTable(v, 60, "first scanline", IndexRange{0, 1});
  expectSameTable(v, 60, "empty band", IndexRange{30, 30});
  const SliceTable whole = SliceTable::build(v, 60), band = SliceTable::build(v, 60, IndexRange{17, 41});
  EXPECT_GT(whole.sliceCount(), band.sliceCount());
  EXPECT_EQ(band.sliceCount(), whole.offsets()[41] - whole.offsets()[17]);
}

// A share of a split job transforms only the triangle runs that reach its
// band: its scanlines get the same slices, in the same order, as from the
// whole scene's transform, in every row of the share.
TEST(TriangleRuns, ABandTransformsOnlyWhatReachesItAndSlicesTheSame) {
  // A sphere of 9600 triangles in shuffled order: runs come from sorting.
  Scene scene = test::sphereScene(0.5f, 60, 80);
  std::shuffle(scene.triangles.begin(), scene.triangles.end(), std::mt19937(3));
  const shading::VertexColors colors = shading::litVertexColors(scene);
  const TriangleRuns runs = TriangleRuns::of(scene);
  const ShearingCamera whole(cameraFor(scene, 160, 120), 160, 120, 9, 3);
  // Bands at the sphere's top and bottom edges (row 1) and across its middle.
  const SliceTable full = SliceTable::build(transformToExtremes(scene, colors, whole, 1), 120);
  int first = 0, last = 119;
  while (first < 119 && full.scanline(first).empty()) ++first;
  while (last > 0 && full.scanline(last).empty()) --last;
  ASSERT_LT(first, last);
  const int middle = (first + last) / 2;
  for (const IndexRange band : {IndexRange{middle - 6, middle + 6}, IndexRange{first, first + 2}, IndexRange{last, last + 1}}) {
    const ShearingCamera share = whole.withShare({{1, 3}, band, {0, 9}});
    ExtremeVertices all = transformToExtremes(scene, colors, share, 0);
    ExtremeVertices culled = transformToExtremes(scene, colors, share, 0, {}, 0, &runs);
    ASSERT_EQ(culled.vertexCount(), all.vertexCount());  // indices stay the scene's
    if (band.begin == middle - 6) {
      EXPECT_LT(culled.triangles.size(), all.triangles.size() / 4) << "a tenth of the rows";
    }
    size_t slices = 0;
    for (int row = 1; row < 3; ++row) {
      moveToRow(all, row);
      moveToRow(culled, row);
      const SliceTable a = SliceTable::build(all, 120, band), b = SliceTable::build(culled, 120, band);
      ASSERT_EQ(a.sliceCount(), b.sliceCount()) << "band " << band.begin << " row " << row;
      slices += a.sliceCount();
      for (int j = band.begin; j < band.end; ++j) {
        ASSERT_EQ(a.scanline(j).size(), b.scanline(j).size()) << j;
        for (size_t k = 0; k < a.scanline(j).size(); ++k) {
          const auto [a0, a1] = sliceEnds(all, a.scanline(j)[k]);
          const auto [b0, b1] = sliceEnds(culled, b.scanline(j)[k]);
          for (const auto& [x, y] : {std::pair{a0, b0}, std::pair{a1, b1}}) {
            EXPECT_EQ(x.x0, y.x0) << j;
            EXPECT_EQ(x.dx, y.dx) << j;
            EXPECT_EQ(x.depth, y.depth) << j;
          }
        }
      }
    }
    EXPECT_GT(slices, 0u) << "band " << band.begin;
  }
}

// Vertices exactly on scanline centres, flat (horizontal) triangles,
// triangles wholly above or below the image, one spanning every scanline,
// degenerate ones, and no triangles at all.
TEST(GpuSlicer, MatchesTheCpuSlicerOnEdgeCases) {
  test::sharedContext();
  const int height = 16;
  ExtremeVertices v;
  auto add = [&](float y0, float y1, float y2) {
    const auto base = uint32_t(v.y.size());
    for (float y : {y0, y1, y2}) {
      v.x0.push_back(3.0f * float(v.y.size() % 5));
      v.dx.push_back(0.25f * float(v.y.size() % 3) - 0.25f);
      v.y.push_back(y);
      v.depth.push_back(0.5f);
      v.invW.push_back(1.0f);
      v.frontOverW.emplace_back(1.0f);
      v.backOverW.emplace_back(1.0f);
    }
    v.triangles.emplace_back(base, base + 1, base + 2);
    v.cullBack.push_back(0);
  };
  expectSameTable(v, height, "empty");
  add(0.5f, 3.5f, 8.5f);       // every corner on a centre
  add(4.0f, 4.0f, 4.0f);       // flat
  add(2.5f, 2.5f, 9.0f);       // flat top on a centre
  add(-9.0f, -5.0f, -1.0f);    // above
  add(20.0f, 30.0f, 25.0f);    // below
  add(-100.0f, 50.0f, 200.0f); // every scanline
  add(7.5f, 7.5f, 7.5f);       // a point on a centre
  add(15.49f, 15.51f, 15.5f);  // the last centre
  expectSameTable(v, height, "edge cases");
}

}  // namespace
}  // namespace mvr
