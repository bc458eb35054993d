#include "shading/texture_set.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "mvr/error.h"
#include "mvr/image.h"
#include "mvr/io/image_file.h"

namespace mvr::shading {
namespace {

int wrap(int i, int n) { return ((i % n) + n) % n; }

}  // namespace

TextureSet TextureSet::load(const Scene& scene) {
  TextureSet set;
  std::map<std::string, int> layerOf;
  std::vector<Image> images;
  for (const Material& m : scene.materials) {
    if (m.texture.empty()) {
      set.materialLayer_.push_back(-1);
      continue;
    }
    auto [it, added] = layerOf.emplace(m.texture, int(images.size()));
    if (added) {
      images.push_back(m.textureImage ? *m.textureImage : readImage(m.texture));
      set.width_ = std::max(set.width_, images.back().width);
      set.height_ = std::max(set.height_, images.back().height);
    }
    set.materialLayer_.push_back(it->second);
  }
  set.layers_ = int(images.size());
  if (set.empty()) return set;
  const int w = set.width_, h = set.height_;
  std::vector<uint8_t> base;
  for (const Image& img : images) {
    std::vector<uint8_t> layer = resampleSrgb8(img, {0, 0, img.width, img.height}, w, h, true);
    base.insert(base.end(), layer.begin(), layer.end());
  }
  set.levelSize_.push_back({w, h});
  set.levels_.push_back(std::move(base));
  // Box-filtered chain down to 1 x 1 (odd sizes drop the last texel),
  // averaged in linear light. Texels are stored as GL_SRGB8_ALPHA8 stores
  // them (decodeSrgb8).
  while (set.levelSize_.back() != glm::ivec2(1)) {
    const glm::ivec2 from = set.levelSize_.back(), to = glm::max(from / 2, glm::ivec2(1));
    const std::vector<uint8_t>& src = set.levels_.back();
    std::vector<uint8_t> dst(size_t(to.x) * to.y * 4 * set.layers_);
    for (int l = 0; l < set.layers_; ++l)
      for (int y = 0; y < to.y; ++y)
        for (int x = 0; x < to.x; ++x) {
          glm::vec4 sum(0.0f);
          for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) {
              const int sx = std::min(2 * x + dx, from.x - 1), sy = std::min(2 * y + dy, from.y - 1);
              sum += decodeSrgb8(&src[((size_t(l) * from.y + sy) * from.x + sx) * 4]);
            }
          encodeSrgb8(sum / 4.0f, &dst[((size_t(l) * to.y + y) * to.x + x) * 4]);
        }
    set.levelSize_.push_back(to);
    set.levels_.push_back(std::move(dst));
  }
  return set;
}

glm::vec4 TextureSet::texel(int layer, int level, int x, int y) const {
  const glm::ivec2 s = levelSize_[level];
  return decodeSrgb8(levels_[level].data() +
                     ((size_t(layer) * s.y + wrap(y, s.y)) * s.x + wrap(x, s.x)) * 4);
}

glm::vec4 TextureSet::bilinear(int layer, int level, glm::vec2 uv) const {
  const glm::ivec2 s = levelSize_[level];
  const float sx = uv.x * s.x - 0.5f, sy = uv.y * s.y - 0.5f;
  const float fx0 = std::floor(sx), fy0 = std::floor(sy);
  const int x0 = int(fx0), y0 = int(fy0);
  const float fx = sx - fx0, fy = sy - fy0;
  return glm::mix(glm::mix(texel(layer, level, x0, y0), texel(layer, level, x0 + 1, y0), fx),
                  glm::mix(texel(layer, level, x0, y0 + 1), texel(layer, level, x0 + 1, y0 + 1), fx),
                  fy);
}

glm::vec4 TextureSet::sample(int layer, glm::vec2 uv, float lod) const {
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return glm::vec4(0.0f);
  uv -= glm::floor(uv);  // repeat; keeps float precision for large uv
  lod = std::clamp(std::isfinite(lod) ? lod : 0.0f, 0.0f, float(levels() - 1));
  const int l0 = int(std::floor(lod)), l1 = std::min(l0 + 1, levels() - 1);
  return glm::mix(bilinear(layer, l0, uv), bilinear(layer, l1, uv), lod - float(l0));
}

float TextureSet::lodFor(glm::vec2 duv) const {
  const float texels = glm::length(duv * glm::vec2(width_, height_));
  return texels > 0.0f ? std::log2(texels) : 0.0f;
}

gl::Texture TextureSet::upload() const {
  gl::Texture tex(GL_TEXTURE_2D_ARRAY);
  // sRGB texels: GL decodes them to linear before filtering.
  gl::TextureStorage3D(tex.id(), levels(), GL_SRGB8_ALPHA8, width_, height_, layers_);
  gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (int l = 0; l < levels(); ++l)
    gl::TextureSubImage3D(tex.id(), l, 0, 0, 0, levelSize_[l].x, levelSize_[l].y, layers_, GL_RGBA,
                          GL_UNSIGNED_BYTE, levels_[l].data());
  tex.filter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
  tex.wrap(GL_REPEAT);
  gl::checkError("uploading textures");
  return tex;
}

}  // namespace mvr::shading
