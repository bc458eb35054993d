#pragma once
// The scene's textures as one set: every material texture resampled to one
// size (the largest), with one box-filtered MIP chain computed here and
// uploaded unchanged to a GL 2D array texture, so that the CPU back end,
// the 1-D texture vectors and every GL back end filter the same texels.
// Coordinates: u to the right, v up (v = 0 is the image's bottom row);
// wrap mode repeat; trilinear filtering with texel centres at +0.5.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "mvr/gl/gl_handles.h"
#include "mvr/scene.h"

namespace mvr::shading {

class TextureSet {
 public:
  // Loads every distinct texture the materials name (errors name the file).
  static TextureSet load(const Scene& scene);

  bool empty() const { return layers_ == 0; }
  int width() const { return width_; }
  int height() const { return height_; }
  int levels() const { return int(levelSize_.size()); }
  // Per material: its layer, or -1 for none.
  const std::vector<int>& materialLayers() const { return materialLayer_; }

  // Trilinear sample of layer at uv, level of detail lod (clamped).
  glm::vec4 sample(int layer, glm::vec2 uv, float lod) const;
  // Level of detail for a footprint of duv (texture units) per pixel.
  float lodFor(glm::vec2 duv) const;

  // GL 2D array texture with this set's levels (needs a current context).
  gl::Texture upload() const;

 private:
  glm::vec4 texel(int layer, int level, int x, int y) const;
  glm::vec4 bilinear(int layer, int level, glm::vec2 uv) const;

  int width_ = 0, height_ = 0, layers_ = 0;
  std::vector<glm::ivec2> levelSize_;
  std::vector<std::vector<uint8_t>> levels_;  // per level: layers x h x w sRGB RGBA8, row 0 = v 0
  std::vector<int> materialLayer_;
};

}  // namespace mvr::shading
