#include "mvr/image.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "mvr/color.h"

namespace mvr {

std::vector<uint8_t> resampleSrgb8(const Image& src, glm::ivec4 rect, int width, int height,
                                   bool bottomUp) {
  Image out(width, height, PixelType::Srgb8);
  auto at = [&](int px, int py) {
    return src.linear(rect.x + std::clamp(px, 0, rect.z - 1), rect.y + std::clamp(py, 0, rect.w - 1));
  };
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float sx = (x + 0.5f) * rect.z / width - 0.5f, sy = (y + 0.5f) * rect.w / height - 0.5f;
      const int x0 = int(std::floor(sx)), y0 = int(std::floor(sy));
      const float fx = sx - x0, fy = sy - y0;
      const glm::vec4 c = glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), fx),
                                   glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx), fy);
      out.setLinear(x, bottomUp ? height - 1 - y : y, c);
    }
  return {out.bytes.begin(), out.bytes.end()};
}

glm::vec4 Image::pixel(int x, int y) const {
  const size_t i = (size_t(y) * width + x) * 4;
  if (isByteType(type)) return glm::vec4(bytes[i], bytes[i + 1], bytes[i + 2], bytes[i + 3]) / 255.0f;
  glm::vec4 v;
  std::memcpy(&v, bytes.data() + i * 4, sizeof v);
  return v;
}

namespace {

// GL's float -> unorm8 conversion: round to nearest.
uint8_t unorm8(float c) { return uint8_t(std::lrint(std::clamp(c, 0.0f, 1.0f) * 255.0f)); }

}  // namespace

glm::vec4 decodeSrgb8(const uint8_t* p) {
  return {linearOfSrgb8(p[0]), linearOfSrgb8(p[1]), linearOfSrgb8(p[2]), float(p[3]) / 255.0f};
}

void encodeSrgb8(const glm::vec4& v, uint8_t* p) {
  for (int c = 0; c < 3; ++c) p[c] = srgb8(v[c]);
  p[3] = unorm8(v[3]);
}

glm::vec4 Image::linear(int x, int y) const {
  if (type != PixelType::Srgb8) return pixel(x, y);
  return decodeSrgb8(bytes.data() + (size_t(y) * width + x) * 4);
}

void Image::setLinear(int x, int y, const glm::vec4& v) {
  const size_t i = (size_t(y) * width + x) * 4;
  uint8_t* p = bytes.data() + i;
  if (type == PixelType::F32) std::memcpy(bytes.data() + i * 4, &v, sizeof v);
  else if (type == PixelType::Srgb8) encodeSrgb8(v, p);
  else for (int c = 0; c < 4; ++c) p[c] = unorm8(v[c]);
}

}  // namespace mvr
