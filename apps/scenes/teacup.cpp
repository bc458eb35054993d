// Procedural teacup (after Halle's test object): a closed, thick-walled
// surface of revolution with a tube handle and coloured patches.
#include "apps/scenes/teacup.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace {

using glm::vec2;
using glm::vec3;
constexpr float kPi = 3.14159265358979f;

// Cup profile (radius, height) from the outside bottom centre, up the outer
// wall, over the rim and down to the inside bottom centre.
const std::vector<vec2> kProfile = {{0.0f, 0.0f},   {0.5f, 0.0f},   {0.6f, 0.06f},
                                    {0.85f, 0.45f}, {0.98f, 0.9f},  {1.0f, 1.1f},
                                    {0.96f, 1.16f}, {0.92f, 1.1f},  {0.9f, 0.9f},
                                    {0.78f, 0.45f}, {0.5f, 0.14f},  {0.0f, 0.12f}};

vec2 catmullRom(const std::vector<vec2>& p, float t) {
  const float s = t * float(p.size() - 1);
  const int i = std::min(int(s), int(p.size()) - 2);
  const float u = s - float(i);
  const vec2 p0 = p[std::max(i - 1, 0)], p1 = p[i], p2 = p[i + 1],
             p3 = p[std::min(i + 2, int(p.size()) - 1)];
  return 0.5f * ((2.0f * p1) + (-p0 + p2) * u + (2.0f * p0 - 5.0f * p1 + 4.0f * p2 - p3) * u * u +
                 (-p0 + 3.0f * p1 - 3.0f * p2 + p3) * u * u * u);
}

vec3 patchColor(float u, float v) {
  // Halle-style coloured patches: 8 sectors x 5 bands, alternating hues.
  static const vec3 palette[] = {{0.9f, 0.25f, 0.2f}, {0.95f, 0.8f, 0.3f}, {0.25f, 0.6f, 0.9f},
                                 {0.3f, 0.8f, 0.4f},  {0.85f, 0.85f, 0.85f}};
  int sector = int(u * 8.0f) % 8, band = std::min(int(v * 5.0f), 4);
  return palette[(sector + band * 2) % 5];
}

void addGrid(mvr::Scene& s, int nu, int nv, bool closedU, auto&& point, auto&& color) {
  const auto base = unsigned(s.positions.size());
  const int cols = closedU ? nu : nu + 1;
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i < cols; ++i) {
      float u = float(i) / nu, v = float(j) / nv;
      s.positions.push_back(point(u, v));
      s.colors.push_back(color(u, v));
    }
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      unsigned a = base + j * cols + i, b = base + j * cols + (i + 1) % cols;
      unsigned c = a + cols, d = b + cols;
      s.triangles.push_back({a, c, b});
      s.triangles.push_back({b, c, d});
    }
}

}  // namespace

namespace mvr::app {

mvr::Scene makeTeacup(int triangles) {
  mvr::Scene s;
  // Body: 2 nu nv triangles, about 85% of the budget, nu = 2 nv.
  const int nv = std::max(4, int(std::lround(std::sqrt(0.85 * triangles / 4.0))));
  const int nu = 2 * nv;
  // Rings at the poles collapse to one point: weld them after the grid.
  addGrid(s, nu, nv, true,
          [](float u, float v) {
            vec2 p = catmullRom(kProfile, v);
            if (v == 0.0f || v == 1.0f) p.x = 0.0f;
            return vec3(p.x * std::cos(2 * kPi * u), p.y - 0.58f, p.x * std::sin(2 * kPi * u));
          },
          patchColor);
  // Handle: a tube along a half ellipse on the +x side, ends in the wall.
  const int ku = std::max(3, int(std::lround(std::sqrt(0.15 * triangles / 4.0))));
  const int kv = 2 * ku;
  addGrid(s, ku, kv, true,
          [](float u, float v) {
            float a = kPi * (v - 0.5f);  // -90..90 degrees around the handle
            vec3 centre(0.88f + 0.38f * std::cos(a), 0.05f + 0.32f * std::sin(a), 0.0f);
            vec3 radial(std::cos(a), std::sin(a), 0.0f), side(0, 0, 1);
            float t = 2 * kPi * u;
            return centre + 0.07f * (std::cos(t) * radial + std::sin(t) * side);
          },
          [](float, float) { return vec3(0.9f, 0.9f, 0.85f); });
  // Weld the pole rings of the body so the surface is closed.
  const int cols = nu;
  for (auto& t : s.triangles)
    for (int k = 0; k < 3; ++k) {
      if (t[k] < unsigned(cols)) t[k] = 0;
      else if (t[k] >= unsigned(nv * cols) && t[k] < unsigned((nv + 1) * cols)) t[k] = nv * cols;
    }
  std::erase_if(s.triangles, [](const glm::uvec3& t) { return t.x == t.y || t.y == t.z || t.x == t.z; });
  s.materialIds.assign(s.triangles.size(), 0);
  s.materials.emplace_back();
  mvr::computeVertexNormals(s);
  return s;
}

}  // namespace mvr::app
