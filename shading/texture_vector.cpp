#include "shading/texture_vector.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

#include "mvr/error.h"

namespace mvr::shading {

int TextureVectors::lengthFor(float widthPixels) {
  const int k = std::clamp(int(std::ceil(std::isfinite(widthPixels) ? widthPixels : 1.0f)), 1, kMaxLength);
  return int(std::bit_ceil(unsigned(k)));
}

int TextureVectors::add(const TextureSet& textures, int layer, glm::vec2 uv0w, glm::vec2 uv1w,
                        float iw0, float iw1, float widthPixels) {
  const int k = lengthFor(widthPixels);
  const int base = int(texels_.size());
  auto uvAt = [&](float u) {
    return (uv0w + (uv1w - uv0w) * u) / (iw0 + (iw1 - iw0) * u);
  };
  for (int i = 0; i < k; ++i) {
    const float u = (i + 0.5f) / k;
    // Footprint of one vector texel on the texture: the level to read.
    const glm::vec2 duv = uvAt(std::min(1.0f, u + 0.5f / k)) - uvAt(std::max(0.0f, u - 0.5f / k));
    texels_.push_back(textures.sample(layer, uvAt(u), textures.lodFor(layer, duv)));
  }
  addLevels(base, k);
  return base;
}

int TextureVectors::addTexels(std::span<const glm::vec4> level0) {
  const size_t k = level0.size();
  if (k == 0 || k > size_t(kMaxLength) || !std::has_single_bit(k))
    fail("texture vector", "length " + std::to_string(k) + " is not a power of two up to " +
                               std::to_string(kMaxLength));
  const int base = int(texels_.size());
  texels_.insert(texels_.end(), level0.begin(), level0.end());
  addLevels(base, int(k));
  return base;
}

int TextureVectors::append(const TextureVectors& from, int base, int length) {
  const int at = int(texels_.size());
  const auto first = from.texels_.begin() + base;
  texels_.insert(texels_.end(), first, first + (2 * length - 1));
  return at;
}

int TextureVectors::append(const TextureVectors& from) {
  const int at = int(texels_.size());
  texels_.insert(texels_.end(), from.texels_.begin(), from.texels_.end());
  return at;
}

// The box-filtered MIP chain after level 0 (k texels at base).
void TextureVectors::addLevels(int base, int k) {
  for (int len = k / 2, from = base; len >= 1; from += 2 * len, len /= 2)
    for (int i = 0; i < len; ++i)
      texels_.push_back(0.5f * (texels_[from + 2 * i] + texels_[from + 2 * i + 1]));
}

// Keep in step with the GLSL below.
glm::vec4 TextureVectors::sample(int base, int k, float u, float texelsPerPixel) const {
  if (k == 1) return texels_[size_t(base)];  // what the mixes below give, without their rounding
  const int maxLevel = std::countr_zero(unsigned(k));
  const float lod = std::clamp(std::log2(std::max(texelsPerPixel, 1.0f)), 0.0f, float(maxLevel));
  auto level = [&](int l) {
    const int len = k >> l, start = base + 2 * k - (2 * k >> l);
    const float s = std::clamp(u, 0.0f, 1.0f) * len - 0.5f;
    const float f0 = std::floor(s);
    const int i0 = std::clamp(int(f0), 0, len - 1), i1 = std::clamp(int(f0) + 1, 0, len - 1);
    return glm::mix(texels_[start + i0], texels_[start + i1], s - f0);
  };
  const int l0 = int(std::floor(lod)), l1 = std::min(l0 + 1, maxLevel);
  return glm::mix(level(l0), level(l1), lod - float(l0));
}

const char* glslTextureVector() {
  return R"(
vec4 textureVectorLevel(samplerBuffer vectors, int base, float k, int l, float u) {
  float len = k / float(1 << l);
  int start = base + int(2.0 * k - 2.0 * len);
  float s = clamp(u, 0.0, 1.0) * len - 0.5;
  float f0 = floor(s);
  int i0 = int(clamp(f0, 0.0, len - 1.0)), i1 = int(clamp(f0 + 1.0, 0.0, len - 1.0));
  return mix(texelFetch(vectors, start + i0), texelFetch(vectors, start + i1), s - f0);
}
vec4 sampleTextureVector(samplerBuffer vectors, int base, float k, float u, float texelsPerPixel) {
  if (k == 1.0) return texelFetch(vectors, base);
  float maxLevel = log2(k);
  float lod = clamp(log2(max(texelsPerPixel, 1.0)), 0.0, maxLevel);
  int l0 = int(floor(lod)), l1 = min(l0 + 1, int(maxLevel));
  return mix(textureVectorLevel(vectors, base, k, l0, u),
             textureVectorLevel(vectors, base, k, l1, u), lod - float(l0));
}
)";
}

}  // namespace mvr::shading
