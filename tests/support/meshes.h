#pragma once
// Meshes built in code for tests that need a shape of known extent.
#include <cmath>

#include <glm/gtc/constants.hpp>

#include "mvr/scene.h"

namespace mvr::test {

// Appends a quad facing +z, its lower left corner at `low`, `size` wide
// and high, white, uv 0 to 1 across it, as two triangles of `material`.
inline void addQuad(Scene& s, glm::vec3 low, glm::vec2 size, uint32_t material) {
  const auto base = uint32_t(s.positions.size());
  for (int c = 0; c < 4; ++c) {
    const glm::vec2 corner(float(c & 1), float(c >> 1));
    s.positions.push_back(low + glm::vec3(corner * size, 0.0f));
    s.normals.emplace_back(0.0f, 0.0f, 1.0f);
    s.colors.emplace_back(1.0f);
    s.uvs.push_back(corner);
  }
  s.triangles.push_back({base, base + 1, base + 3});
  s.triangles.push_back({base, base + 3, base + 2});
  s.materialIds.insert(s.materialIds.end(), 2, material);
}

// A UV sphere of radius r at the origin, grey, under an ambient light of 1.
inline Scene sphereScene(float r, int rings, int segments) {
  Scene s;
  const float pi = glm::pi<float>();
  for (int i = 0; i <= rings; ++i)
    for (int k = 0; k <= segments; ++k) {
      const float th = pi * float(i) / float(rings), ph = 2.0f * pi * float(k) / float(segments);
      const glm::vec3 n(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
      s.positions.push_back(r * n);
      s.normals.push_back(n);
      s.colors.push_back(glm::vec3(0.6f));
    }
  for (int i = 0; i < rings; ++i)
    for (int k = 0; k < segments; ++k) {
      const uint32_t a = uint32_t(i * (segments + 1) + k), b = a + 1, c = a + uint32_t(segments + 1), d = c + 1;
      // Counter-clockwise seen from outside: a two-sided material lights a
      // back face by its flipped normal.
      s.triangles.push_back({a, b, c});
      s.triangles.push_back({b, d, c});
    }
  s.materialIds.assign(s.triangles.size(), 0);
  Material m;
  m.diffuse = glm::vec3(1);
  s.materials = {m};
  s.ambient = glm::vec3(1);
  return s;
}

}  // namespace mvr::test
