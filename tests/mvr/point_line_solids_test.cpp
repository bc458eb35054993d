// Points and lines drawn as small solids (mvr/assets/point_line_solids.h):
// their shapes, sizes and windings by hand, and the loaders that use them
// (OBJ `p` and `l`, a bare OBJ or PLY point cloud, glTF's point and line
// modes).
#include <cmath>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "mvr/assets/mesh_io.h"
#include "mvr/assets/point_line_solids.h"
#include "tests/support/file_test.h"
#include "tests/support/gltf_document.h"

namespace mvr {
namespace {

class PointLineSolids : public test::FileTest {};

// Every triangle faces away from `inside(p)`, the point its centroid is
// measured from (a dot's centre, the nearest point of a stroke's axis).
template <class Inside>
void expectWoundOutward(const Scene& s, Inside inside) {
  for (const glm::uvec3& t : s.triangles) {
    const glm::vec3 a = s.positions[t.x], b = s.positions[t.y], c = s.positions[t.z];
    const glm::vec3 centroid = (a + b + c) / 3.0f;
    EXPECT_GT(glm::dot(glm::cross(b - a, c - a), centroid - inside(centroid)), 0.0f);
    for (uint32_t v : {t.x, t.y, t.z}) EXPECT_GT(glm::dot(s.normals[v], s.positions[v] - inside(s.positions[v])), 0.0f);
  }
}

// Two points 10 apart: each an octahedron of radius 1% of the diagonal.
TEST_F(PointLineSolids, PointIsAnOctahedronWoundOutward) {
  Scene s;
  PointLineSet set;
  set.addPoint({glm::vec3(0), glm::vec3(1, 0, 0)}, 0);
  set.addPoint({glm::vec3(10, 0, 0), glm::vec3(0, 1, 0)}, 0);
  addPointLineSolids(s, set);
  ASSERT_EQ(s.positions.size(), 12u);
  ASSERT_EQ(s.triangles.size(), 16u);
  EXPECT_EQ(s.materialIds.size(), 16u);
  for (size_t v = 0; v < 6; ++v) {
    EXPECT_NEAR(glm::length(s.positions[v]), 0.1f, 1e-6f);
    EXPECT_EQ(s.colors[v], glm::vec3(1, 0, 0));
    EXPECT_EQ(s.colors[v + 6], glm::vec3(0, 1, 0));
  }
  expectWoundOutward(s, [](glm::vec3 p) { return p.x > 5 ? glm::vec3(10, 0, 0) : glm::vec3(0); });
}

// A segment along a diagonal: a square prism of half-width 0.4% of its
// length, every side facing away from the axis.
TEST_F(PointLineSolids, SegmentIsAPrismWoundOutward) {
  Scene s;
  PointLineSet set;
  const glm::vec3 a(1, 2, 3), b(4, 6, 3);  // length 5
  set.addSegment({a}, {b}, 0);
  addPointLineSolids(s, set);
  ASSERT_EQ(s.positions.size(), 8u);
  ASSERT_EQ(s.triangles.size(), 8u);
  const glm::vec3 u = glm::normalize(b - a);
  auto axis = [&](glm::vec3 p) { return a + glm::dot(p - a, u) * u; };
  for (const glm::vec3& p : s.positions) EXPECT_NEAR(glm::distance(p, axis(p)), 0.02f, 1e-5f);
  expectWoundOutward(s, axis);
}

// Denser sets get smaller marks: 10,000 points, radius 0.5% of the diagonal.
TEST_F(PointLineSolids, DenseCloudsGetSmallerDots) {
  Scene s;
  PointLineSet set;
  for (int i = 0; i < 100; ++i)
    for (int j = 0; j < 100; ++j) set.addPoint({glm::vec3(i, j, 0) * (1.0f / 99.0f)}, 0);
  addPointLineSolids(s, set);
  EXPECT_NEAR(glm::distance(s.positions[0], glm::vec3(0)), 0.005f * std::sqrt(2.0f), 1e-6f);
}

TEST_F(PointLineSolids, LoadersDrawPointsAndLines) {
  // The edges of a unit square as one polyline, and a point.
  const Scene obj = loadMesh(write("lines.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nl 1 2 3 4 1\np 3\n"));
  EXPECT_EQ(obj.triangles.size(), 4u * 8 + 8);
  const Scene cloud = loadMesh(write("cloud.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"));
  EXPECT_EQ(cloud.triangles.size(), 3u * 8);
  const Scene ply = loadMesh(write("cloud.ply", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                                                "property float z\nend_header\n0 0 0\n1 1 1\n"));
  EXPECT_EQ(ply.triangles.size(), 2u * 8);
  // glTF: a LINE_LOOP of three vertices (three segments) beside a triangle.
  test::Document d;
  const int p = d.positions({0, 0, 0, 1, 0, 0, 0, 1, 0});
  d.json["meshes"] = nlohmann::json::array(
      {{{"primitives", nlohmann::json::array({{{"attributes", {{"POSITION", p}}}, {"mode", 2}},
                                               {{"attributes", {{"POSITION", p}}}}})}}});
  d.json["nodes"] = nlohmann::json::array({{{"mesh", 0}, {"translation", {0, 0, 5}}}});
  const Scene gltf = loadMesh(d.write(dir_ / "loop.gltf"));
  ASSERT_EQ(gltf.triangles.size(), 1u + 3 * 8);
  for (const glm::vec3& v : gltf.positions) EXPECT_NEAR(v.z, 5.0f, 0.05f);  // placed by the node
}

}  // namespace
}  // namespace mvr
