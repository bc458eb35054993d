#pragma once
// Points and lines, which have no area for a surface renderer to fill, as
// small solids so that a point cloud or a wireframe a file holds is drawn:
// a point as an octahedron (6 vertices, 8 triangles, normals pointing out
// from its centre), a line segment as a square prism without caps (8
// vertices, 8 triangles, normals pointing out from its axis). Sized to the
// scene: a point's radius is min(1%, 50% / sqrt(points)) of the diagonal of
// the bounds of everything (so a dense cloud's dots do not merge), a
// segment's half-width min(0.4%, 20% / sqrt(segments)) of it.
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "mvr/scene.h"

namespace mvr {

struct PointLineSet {
  struct Mark {
    glm::vec3 position;
    glm::vec3 color{1.0f};  // a vertex colour, as Scene::colors
  };
  std::vector<Mark> points;
  std::vector<uint32_t> pointMaterials;
  std::vector<std::pair<Mark, Mark>> segments;
  std::vector<uint32_t> segmentMaterials;

  bool empty() const { return points.empty() && segments.empty(); }
  void addPoint(const Mark& m, uint32_t material) { points.push_back(m), pointMaterials.push_back(material); }
  void addSegment(const Mark& a, const Mark& b, uint32_t material) {
    segments.emplace_back(a, b), segmentMaterials.push_back(material);
  }
};

// Appends the set's solids to the scene (materials: indices into its own).
void addPointLineSolids(Scene& scene, const PointLineSet& set);

}  // namespace mvr
