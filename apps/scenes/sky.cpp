#include "apps/scenes/sky.h"

#include <algorithm>
#include <cmath>

#include "shading/cube_faces.h"

namespace mvr::app {
namespace {

// Radiance in linear light, stored sRGB-encoded as image files are.
void put(Image& img, int x, int y, const glm::vec3& c) { img.setLinear(x, y, glm::vec4(c, 1.0f)); }

// Inverse of GL_SPHERE_MAP: the view ray (0, 0, -1) mirrored by the ball's
// normal h at sphere-map coordinates (s, t); the rim stands for the rest.
glm::vec3 sphereDirection(float s, float t) {
  glm::vec2 xy(2.0f * s - 1.0f, 2.0f * t - 1.0f);
  const float len = glm::length(xy);
  if (len > 1.0f) xy /= len;
  const glm::vec3 h(xy, std::sqrt(std::max(0.0f, 1.0f - glm::dot(xy, xy))));
  return glm::vec3(0.0f, 0.0f, -1.0f) + 2.0f * h.z * h;
}

}  // namespace

glm::vec3 skyRadiance(glm::vec3 d) {
  d = glm::normalize(d);
  const glm::vec3 sun = glm::normalize(glm::vec3(0.4f, 0.6f, 0.7f));
  if (glm::dot(d, sun) > 0.99f) return {1.0f, 0.95f, 0.8f};
  if (std::abs(d.y) < 0.12f) {
    // Hue from the azimuth: red towards +x, green +z, blue -x.
    const float a = std::atan2(d.z, d.x);
    return 0.5f + 0.4f * glm::vec3(std::cos(a), std::cos(a - 2.0944f), std::cos(a + 2.0944f));
  }
  if (d.y > 0.0f) return glm::mix(glm::vec3(0.85f, 0.9f, 1.0f), glm::vec3(0.2f, 0.4f, 0.85f), d.y);
  const glm::vec2 ground = glm::vec2(d.x, d.z) / -d.y;  // on the plane y = -1
  const bool dark = (int(std::floor(ground.x)) + int(std::floor(ground.y))) & 1;
  return dark ? glm::vec3(0.25f, 0.2f, 0.15f) : glm::vec3(0.6f, 0.5f, 0.35f);
}

Image makeSkyCube(int face) {
  Image img(6 * face, face, PixelType::Srgb8);
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < face; ++y)
      for (int x = 0; x < face; ++x) {
        const float sc = 2.0f * (x + 0.5f) / face - 1.0f, tc = 2.0f * (y + 0.5f) / face - 1.0f;
        put(img, f * face + x, y, skyRadiance(shading::cubeDirection(f, sc, tc)));
      }
  return img;
}

Image makeSkySpherePair(int size) {
  Image img(2 * size, size, PixelType::Srgb8);
  for (int half = 0; half < 2; ++half)
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        // Image rows run down; t runs up.
        glm::vec3 d = sphereDirection((x + 0.5f) / size, 1.0f - (y + 0.5f) / size);
        if (half == 1) d = glm::vec3(-d.x, d.y, -d.z);
        put(img, half * size + x, y, skyRadiance(d));
      }
  return img;
}

Image makeSkyEquirect(int width, float sunScale) {
  const int height = width / 2;
  Image img(width, height, PixelType::F32);
  const glm::vec3 sun = glm::normalize(glm::vec3(0.4f, 0.6f, 0.7f));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float phi = (2.0f * (x + 0.5f) / width - 1.0f) * float(M_PI);  // atan2(z, x)
      const float lat = (0.5f - (y + 0.5f) / height) * float(M_PI);
      const glm::vec3 d(std::cos(lat) * std::cos(phi), std::sin(lat), std::cos(lat) * std::sin(phi));
      const glm::vec3 c = skyRadiance(d) * (glm::dot(d, sun) > 0.99f ? sunScale : 1.0f);
      img.setLinear(x, y, glm::vec4(c, 1.0f));
    }
  return img;
}

}  // namespace mvr::app
