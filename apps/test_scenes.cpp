#include "apps/test_scenes.h"

#include <algorithm>
#include <array>
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

namespace {

// A quad a, b, c, d (counter-clockwise seen from its front) with one
// colour per corner.
void addQuad(Scene& s, const std::array<glm::vec3, 4>& p, const std::array<glm::vec3, 4>& c) {
  const auto b = unsigned(s.positions.size());
  const glm::vec3 n = glm::normalize(glm::cross(p[1] - p[0], p[3] - p[0]));
  for (int k = 0; k < 4; ++k) {
    s.positions.push_back(p[k]);
    s.colors.push_back(c[k]);
    s.normals.push_back(n);
  }
  s.triangles.push_back({b, b + 1, b + 2});
  s.triangles.push_back({b, b + 2, b + 3});
}

}  // namespace

Scene makeThinAndDeepScene(int bars) {
  Scene s;
  // The box: opening at z = 0.3, back wall at z = -1.5; walls shade from
  // the rim's colour to the back's, so a revealed strip of wall shows.
  const float x = 0.8f, y = 0.6f, front = 0.3f, back = -1.5f;
  const glm::vec3 rim(0.9f, 0.8f, 0.3f), deep(0.2f, 0.3f, 0.8f);
  addQuad(s, {{{-x, -y, back}, {x, -y, back}, {x, y, back}, {-x, y, back}}}, {deep, deep, deep, deep});
  addQuad(s, {{{-x, -y, front}, {-x, -y, back}, {-x, y, back}, {-x, y, front}}}, {rim, deep, deep, rim});
  addQuad(s, {{{x, -y, back}, {x, -y, front}, {x, y, front}, {x, y, back}}}, {deep, rim, rim, deep});
  addQuad(s, {{{-x, y, front}, {-x, y, back}, {x, y, back}, {x, y, front}}}, {rim, deep, deep, rim});
  addQuad(s, {{{-x, -y, back}, {-x, -y, front}, {x, -y, front}, {x, -y, back}}}, {deep, rim, rim, deep});
  // The bars: 0.012 wide (about a pixel at 160 pixels over 2 units),
  // between z = 0.4 and 1.0, grey to white.
  for (int i = 0; i < bars; ++i) {
    const float f = (i + 0.5f) / float(bars);
    const float bx = -0.9f + 1.8f * f, z = 0.4f + 0.6f * std::fmod(f * 7.0f, 1.0f), w = 0.006f;
    const glm::vec3 c(0.5f + 0.5f * f);
    addQuad(s, {{{bx - w, -0.8f, z}, {bx + w, -0.8f, z}, {bx + w, 0.8f, z}, {bx - w, 0.8f, z}}}, {c, c, c, c});
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
