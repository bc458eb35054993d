#pragma once
// A cube map's faces as GL 4.5's table 8.19 lays them out: +X -X +Y -Y +Z
// -Z, each with s to the right and t down. Shared by the reflection maps
// (EnvironmentSet) and the image-based light (ImageLight).
#include <glm/glm.hpp>

namespace mvr::shading {

// The face direction r points through, and its coordinates st in [0, 1]^2.
inline int cubeFace(const glm::vec3& r, glm::vec2& st) {
  const glm::vec3 a = glm::abs(r);
  int face;
  float sc, tc, ma;
  if (a.x >= a.y && a.x >= a.z) {
    face = r.x >= 0 ? 0 : 1, ma = a.x, sc = r.x >= 0 ? -r.z : r.z, tc = -r.y;
  } else if (a.y >= a.z) {
    face = r.y >= 0 ? 2 : 3, ma = a.y, sc = r.x, tc = r.y >= 0 ? r.z : -r.z;
  } else {
    face = r.z >= 0 ? 4 : 5, ma = a.z, sc = r.z >= 0 ? r.x : -r.x, tc = -r.y;
  }
  st = 0.5f * (glm::vec2(sc, tc) / ma + 1.0f);
  return face;
}

// Its inverse: the (unnormalised) direction through (sc, tc) in [-1, 1]^2
// of a face, or beyond it on the face's plane.
inline glm::vec3 cubeDirection(int face, float sc, float tc) {
  switch (face) {
    case 0: return {1.0f, -tc, -sc};
    case 1: return {-1.0f, -tc, sc};
    case 2: return {sc, 1.0f, tc};
    case 3: return {sc, -1.0f, -tc};
    case 4: return {sc, -tc, 1.0f};
    default: return {-sc, -tc, -1.0f};
  }
}

}  // namespace mvr::shading
