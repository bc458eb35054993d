#pragma once
// Bilinear filtering as GL's GL_LINEAR does it, at texel coordinates
// (fx, fy) whose texel centres lie at whole numbers: at(x, y) gives texel
// (x, y), clamped or wrapped as its caller's edges are. Shared by the
// reflection maps and the image-based light, whose C++ lookups read the
// texels their GL copies do.
#include <cmath>

#include <glm/glm.hpp>

namespace mvr::shading {

template <class At>
glm::vec3 bilinear(float fx, float fy, const At& at) {
  const float x0 = std::floor(fx), y0 = std::floor(fy), tx = fx - x0, ty = fy - y0;
  const int x = int(x0), y = int(y0);
  return glm::mix(glm::mix(at(x, y), at(x + 1, y), tx), glm::mix(at(x, y + 1), at(x + 1, y + 1), tx), ty);
}

}  // namespace mvr::shading
