// What the finer outline needs, by hand: the pixels a slicer reads (covered
// beside an empty one) and the triangles that reach a sample within a
// pixel of one of them, kept in the scene's order; a triangle behind the
// eye is kept because its bounds are unknown.
#include <gtest/gtest.h>

#include <vector>

#include "mvr/views/outline_triangles.h"

namespace mvr {
namespace {

TEST(OutlinePixels, AreTheCoveredOnesBesideAnEmptyOne) {
  // Two rows of 7: a run, a lone pixel and a gap; then a full row, whose
  // image edges are not empty neighbours.
  const std::vector<float> depth = {0, 1, 1, 1, 0, 1, 0,  //
                                    1, 1, 1, 1, 1, 1, 1};
  const std::vector<uint8_t> expected = {0, 1, 0, 1, 0, 1, 0,  //
                                         0, 0, 0, 0, 0, 0, 0};
  EXPECT_EQ(outlinePixels(depth, 7, 2), expected);
}

// x, y in window pixels of an 8 x 4 window at w = 1 (the matrix below
// divides by z): the position whose projection lands there.
glm::vec3 at(double x, double y, double w = 1.0) {
  return glm::vec3(float((x / 8.0 * 2.0 - 1.0) * w), float((y / 4.0 * 2.0 - 1.0) * w), float(w));
}

TEST(OutlineTriangles, AreThoseReachingASampleWithinAPixelOfAReadOne) {
  glm::dmat4 viewProj(0.0);  // clip = (x, y, 0, z): window x, y of the positions above
  viewProj[0][0] = viewProj[1][1] = viewProj[2][3] = 1.0;
  std::vector<uint8_t> marked(8 * 4, 0);
  marked[1 * 8 + 5] = 1;  // pixel (5, 1): its outline reads columns 4 to 6 of row 1
  Scene scene;
  const auto add = [&](glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const auto v = uint32_t(scene.positions.size());
    scene.positions.insert(scene.positions.end(), {a, b, c});
    scene.triangles.push_back({v, v + 1, v + 2});
  };
  add(at(0.2, 3.2), at(1.8, 3.2), at(1.0, 3.9));  // 0: far from it
  add(at(4.2, 1.2), at(4.8, 1.2), at(4.5, 1.8));  // 1: on row 1's samples in column 4
  add(at(7.1, 0.5), at(7.5, 1.0), at(7.2, 2.0));  // 2: row 1, but column 7
  add(at(4.0, 1.6), at(6.0, 1.6), at(5.0, 2.4));  // 3: between the rows' sample centres
  add(at(5.0, 1.0), at(6.0, 1.0), at(5.5, 1.0, -1.0));  // 4: a corner behind the eye
  add(at(-40.0, -9.0), at(90.0, -9.0), at(20.0, 30.0));  // 5: over the whole window
  const std::vector<uint32_t> indices = outlineTriangles(scene, viewProj, 8, 4, marked);
  const std::vector<uint32_t> expected = {3, 4, 5, 12, 13, 14, 15, 16, 17};
  EXPECT_EQ(indices, expected);
  EXPECT_TRUE(outlineTriangles(scene, viewProj, 8, 4, std::vector<uint8_t>(8 * 4, 0)) ==
              std::vector<uint32_t>({12, 13, 14}));  // nothing read: only the one of unknown bounds
}

}  // namespace
}  // namespace mvr
