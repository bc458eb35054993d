// Split tracks for highlights, by hand: the mirror ray's closest approach
// to the track, and knots at the peak and where the highlight has fallen
// by equal steps.
#include <gtest/gtest.h>

#include "shading/view_dependent.h"
#include "slicing/highlight_splits.h"

namespace mvr {
namespace {

TEST(HighlightSplits, TheMirrorRayMeetsTheTrackWhereTheLinesAreClosest) {
  // From the origin along (-1, 0, 1)/sqrt2 the ray reaches z = 3 at x = -3,
  // 3 sqrt2 along it; a track at y = 0.5 is passed there too.
  double distance = 0;
  const glm::dvec3 up(-std::sqrt(0.5), 0.0, std::sqrt(0.5));
  EXPECT_NEAR(*closestTrackX({0, 0, 0}, up, 0.0, 3.0, &distance), -3.0, 1e-12);
  EXPECT_NEAR(distance, 3.0 * std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(*closestTrackX({0, 0, 0}, up, 0.5, 3.0), -3.0, 1e-12);
  EXPECT_FALSE(closestTrackX({0, 0, 0}, {1, 0, 0}, 0.0, 3.0));   // parallel to the track
  EXPECT_FALSE(closestTrackX({0, 0, 0}, {0, 0, -1}, 0.0, 3.0));  // away from it
}

TEST(HighlightSplits, KnotsAtThePeakAndAtEqualStepsDownTheLobe) {
  // Light straight down on a surface facing the track: the mirror ray
  // goes straight up and meets the track above the point, at x = 0.5.
  Scene scene;
  Material m;
  m.specular = glm::vec3(0.8f);
  m.shininess = 10.0f;
  m.specularModel = SpecularModel::Phong;
  scene.materials = {m, Material{}};
  scene.lights = {Light{Light::Type::Directional, glm::vec3(0, 0, -1), glm::vec3(1)}};
  CameraSpec spec;
  spec.distance = 4, spec.planeWidth = 2, spec.nearDistance = 1, spec.farDistance = 8;
  spec.trackLeft = -4, spec.trackRight = 4;
  const ShearingCamera cam(spec, 32, 8, 9);  // views at x = -4 .. 4, row r = x + 4.5
  const glm::vec3 p(0.5f, 0.0f, 0.0f), n(0, 0, 1);
  std::vector<HighlightKnot> knots;
  EXPECT_EQ(HighlightSplitter(scene, cam, 0, 1).add(p, n, 1, knots), 0);  // not specular
  ASSERT_EQ(HighlightSplitter(scene, cam, 0, 1).add(p, n, 0, knots), 5);
  // Ends, peak, and the pair where cos^10 = 1/2: 4 tan(acos(0.5^0.1)) off.
  const float off = 4.0f * std::tan(std::acos(std::pow(0.5f, 0.1f)));
  const float rows[5] = {0.0f, 5.0f - off, 5.0f, 5.0f + off, 9.0f};
  for (int k = 0; k < 5; ++k) EXPECT_NEAR(knots[k].r, rows[k], 1e-4f) << k;
  EXPECT_NEAR(knots[2].specular.r, 0.8f, 1e-5f);
  EXPECT_NEAR(knots[1].specular.r, 0.4f, 1e-4f);
  EXPECT_NEAR(knots[3].specular.r, 0.4f, 1e-4f);
  // Each knot is the exact highlight for its eye (r = 0 is half a view
  // beyond the track).
  EXPECT_NEAR(knots[0].specular.r, shading::specularLight(scene, m, p, n, {-4.5f, 0.0f, 4.0f}).r, 1e-6f);
  // Without splits only the ends; one view: the ends of its one row.
  knots.clear();
  EXPECT_EQ(HighlightSplitter(scene, cam, 0, 0).add(p, n, 0, knots), 2);
  EXPECT_EQ(HighlightSplitter(scene, ShearingCamera(spec, 32, 8, 1), 0, 3).add(p, n, 0, knots), 2);
  EXPECT_FLOAT_EQ(knots[2].r, 0.0f);
  EXPECT_FLOAT_EQ(knots[3].r, 1.0f);
}

}  // namespace
}  // namespace mvr
