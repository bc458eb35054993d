#include "apps/test_scenes.h"

#include <algorithm>
#include <cmath>

namespace mvr::app {

Scene makeSlenderScene(int count) {
  Scene s;
  for (int i = 0; i < count; ++i) {
    const float f = (i + 0.5f) / count;
    const float x = -1.0f + 2.0f * f, z = 0.6f * std::sin(9.0f * f), w = 0.004f;
    const auto b = unsigned(s.positions.size());
    s.positions.insert(s.positions.end(), {{x - w, -0.9f, z}, {x + w, -0.9f, z}, {x + w, 0.9f, z},
                                           {x - w, 0.9f, z}});
    const glm::vec3 c(0.3f + 0.7f * f, 0.8f - 0.6f * f, 0.5f);
    s.colors.insert(s.colors.end(), 4, c);
    s.normals.insert(s.normals.end(), 4, glm::vec3(0, 0, 1));
    s.triangles.push_back({b, b + 1, b + 2});
    s.triangles.push_back({b, b + 2, b + 3});
  }
  s.materialIds.assign(s.triangles.size(), 0);
  s.materials.emplace_back();
  s.lights.push_back(Light{});
  return s;
}

double averagePolygonHeight(const Scene& scene, const ShearingCamera& cam) {
  const int centre = cam.views() / 2;
  double sum = 0;
  long count = 0;
  for (const glm::uvec3& t : scene.triangles) {
    double lo = INFINITY, hi = -INFINITY;
    for (int k = 0; k < 3; ++k) {
      const double y = cam.project(glm::dvec3(scene.positions[t[k]]), centre).y;
      lo = std::min(lo, y);
      hi = std::max(hi, y);
    }
    lo = std::max(lo, 0.0);
    hi = std::min(hi, double(cam.height()));
    if (hi <= lo) continue;
    sum += hi - lo;
    ++count;
  }
  return count ? sum / count : 0.0;
}

}  // namespace mvr::app
