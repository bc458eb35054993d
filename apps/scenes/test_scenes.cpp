#include "apps/scenes/test_scenes.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

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

Scene makeKnotScene(int triangles) {
  constexpr int kAround = 16;
  constexpr float kPi = 3.14159265358979f, kTube = 0.13f;
  const int along = std::max(8, triangles / (2 * kAround));
  auto curve = [&](float t) {  // the (2, 3) torus knot, scaled to a radius of 1
    const float r = 2.0f + std::cos(3.0f * t);
    return glm::vec3(r * std::cos(2.0f * t), r * std::sin(2.0f * t), std::sin(3.0f * t)) / 3.0f;
  };
  // Ring frames carried along the curve without twisting about it (each
  // normal made perpendicular to the next tangent), then the angle the
  // carried frame has turned by when it comes round spread over the
  // rings, so that the last ring meets the first.
  const auto rings = size_t(along);
  std::vector<glm::vec3> centre(rings), tangent(rings), normal(rings);
  for (int i = 0; i < along; ++i) {
    const float t = 2.0f * kPi * float(i) / float(along), dt = 1e-3f;
    centre[size_t(i)] = curve(t);
    tangent[size_t(i)] = glm::normalize(curve(t + dt) - curve(t - dt));
  }
  normal[0] = glm::normalize(glm::cross(tangent[0], glm::vec3(0, 0, 1)));
  for (int i = 1; i < along; ++i) {
    const glm::vec3 n = normal[size_t(i - 1)], t = tangent[size_t(i)];
    normal[size_t(i)] = glm::normalize(n - glm::dot(n, t) * t);
  }
  const glm::vec3 n0 = normal[0], back = glm::normalize(normal.back() - glm::dot(normal.back(), tangent[0]) * tangent[0]);
  const float turned = std::atan2(glm::dot(glm::cross(back, n0), tangent[0]), glm::dot(back, n0));
  Scene s;
  for (int i = 0; i < along; ++i) {
    const glm::vec3 t = tangent[size_t(i)], b0 = glm::cross(t, normal[size_t(i)]);
    const float f = float(i) / float(along), undo = turned * f;
    const glm::vec3 n = std::cos(undo) * normal[size_t(i)] + std::sin(undo) * b0, b = glm::cross(t, n);
    const glm::vec3 c(0.55f + 0.35f * std::cos(2.0f * kPi * f), 0.55f + 0.35f * std::cos(2.0f * kPi * (f + 1.0f / 3)),
                      0.55f + 0.35f * std::cos(2.0f * kPi * (f + 2.0f / 3)));
    for (int k = 0; k < kAround; ++k) {
      const float a = 2.0f * kPi * float(k) / float(kAround);
      const glm::vec3 radial = std::cos(a) * n + std::sin(a) * b;
      s.positions.push_back(centre[size_t(i)] + kTube * radial);
      s.normals.push_back(radial);
      s.colors.push_back(c);
    }
  }
  for (int i = 0; i < along; ++i)
    for (int k = 0; k < kAround; ++k) {
      auto at = [&](int ii, int kk) { return unsigned((ii % along) * kAround + kk % kAround); };
      const unsigned a = at(i, k), b = at(i + 1, k), c = at(i + 1, k + 1), d = at(i, k + 1);
      s.triangles.push_back({a, b, c});
      s.triangles.push_back({a, c, d});
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
