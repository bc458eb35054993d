#include <gtest/gtest.h>

#include <random>

#include "slicing/extreme_vertices.h"
#include "slicing/slice_table.h"

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
    if (sl.triangle == 0) EXPECT_GT(e1.x0 - e0.x0, 0.0f);
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
