#pragma once
// Halle's MVR texture path (6.5.3): per slice, the texture along the slice
// is extracted once as a 1-D texture vector, perspective-corrected at
// extraction: texel k holds the surface at screen parameter
// u = (k + 0.5) / K. Because a slice's screen parameter names the same
// surface point in every view, every view then resamples the vector
// linearly in u, with no per-pixel divide. K is the wider p-edge's pixel
// width rounded up to a power of two; a 1-D MIP chain (box filter) serves
// the narrower views. Level l (K >> l texels) starts at 2K - (2K >> l).
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "shading/texture_set.h"

namespace mvr::shading {

class TextureVectors {
 public:
  static constexpr int kMaxLength = 4096;

  void clear() { texels_.clear(); }
  void reserve(size_t texels) { texels_.reserve(texels); }
  // Appends every vector of another store; returns where its texel 0 went.
  int append(const TextureVectors& from);
  // Appends the vector of a slice whose ends carry uv / w and 1 / w;
  // returns its first texel. widthPixels: the wider p-edge.
  int add(const TextureSet& textures, int layer, glm::vec2 uv0OverW, glm::vec2 uv1OverW,
          float invW0, float invW1, float widthPixels);
  // Appends a vector of the given level-0 texels (a power of two of them,
  // at most kMaxLength) and its MIP chain; returns its first texel. The
  // image-based back end's source pixel runs are such vectors already.
  int addTexels(std::span<const glm::vec4> level0);
  // Appends a copy of `length` texels' vector at `base` of another store.
  int append(const TextureVectors& from, int base, int length);
  static int lengthFor(float widthPixels);
  // Sample at screen parameter u with `texelsPerPixel` level-0 texels per
  // pixel: linear within a level, linear between levels.
  glm::vec4 sample(int base, int length, float u, float texelsPerPixel) const;

  const std::vector<glm::vec4>& texels() const { return texels_; }

 private:
  void addLevels(int base, int k);

  std::vector<glm::vec4> texels_;
};

// GLSL: `vec4 sampleTextureVector(samplerBuffer, int base, float length,
// float u, float texelsPerPixel)`, the same as TextureVectors::sample. The
// base is an int: texel indices of a whole row's vectors pass 2^24, where
// a float stops counting exactly.
const char* glslTextureVector();

}  // namespace mvr::shading
