#pragma once
// The scene's textures, each at its own size with its own box-filtered MIP
// chain computed here, so that the CPU back end, the 1-D texture vectors
// and every GL back end filter the same texels. On the GL, textures of one
// size share a 2D array (a group); up to kMaxGroups groups, each on its
// own texture unit, and glsl() picks a material's group and layer. A scene
// with more distinct sizes than that has its smallest textures resampled
// up into the smallest group that holds them (rare: exporters write a few
// power-of-two sizes).
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
  static constexpr int kMaxGroups = 8;
  static constexpr unsigned kFirstUnit = 8;  // group g on unit kFirstUnit + g

  // Loads every distinct texture the materials name (errors name the file).
  static TextureSet load(const Scene& scene);

  bool empty() const { return layers_.empty(); }
  // Per material: its layer, or -1 for none. A material with an emission
  // texture and no base texture has a white 1 x 1 one, so that every pass
  // that draws its emission's texels runs over it.
  const std::vector<int>& materialLayers() const { return materialLayer_; }
  // Per material: its emission texture's layer, or -1 for none.
  const std::vector<int>& emissionLayers() const { return emissionLayer_; }
  glm::ivec2 size(int layer) const { return layers_[size_t(layer)].levelSize[0]; }
  int levels(int layer) const { return int(layers_[size_t(layer)].levelSize.size()); }
  // Per material: its GL group and the layer within it ({-1, -1} for none),
  // of the base texture and of the emission texture.
  std::vector<glm::ivec2> materialSlots() const { return slotsOf(materialLayer_); }
  std::vector<glm::ivec2> emissionSlots() const { return slotsOf(emissionLayer_); }

  // Trilinear sample of layer at uv, level of detail lod (clamped).
  glm::vec4 sample(int layer, glm::vec2 uv, float lod) const;
  // Level of detail in layer for a footprint of duv (texture units) per pixel.
  float lodFor(int layer, glm::vec2 duv) const;

  // Per group, a GL 2D array texture with its levels (needs a current
  // context).
  std::vector<gl::Texture> upload() const;

  // GLSL, after shading::glslMaterials(): the groups' samplers and
  //   vec4 materialTexel(int material, vec2 uv, vec2 dx, vec2 dy)
  //     (by textureGrad; vec4(1) for a material without a texture),
  //   vec4 materialTexelLod(int material, vec2 uv, float lod),
  //   vec2 materialTextureSize(int material),
  //   vec3 materialGlow(int material, vec2 uv, vec2 dx, vec2 dy): the
  //     emission times its texture's texel (the emission alone without),
  //   vec4 emissionTexelLod(int material, vec2 uv, float lod): the
  //     emission texture's texel (vec4(1) without),
  //   vec2 emissionTextureSize(int material).
  static const std::string& glsl();
  // GLSL after glsl() and glslMaterials() (view_dependent.h): `vec4
  // surfaceTexel(int material, vec2 uv)`, the texel with the screen's
  // gradients, a cut-out's texel below its cut-off discarded (MASK). Call
  // it before any other discard: the gradients need the whole quad. With
  // EMISSION_TEXTURE also `vec3 surfaceGlow(int material, vec2 uv)`, the
  // emission at uv by the screen's gradients (call it there too).
  static const char* glslSurfaceTexel();

 private:
  struct Layer {
    std::vector<glm::ivec2> levelSize;
    std::vector<std::vector<uint8_t>> levels;  // sRGB RGBA8, row 0 = v 0
    int group = 0, slice = 0;
  };
  glm::vec4 texel(const Layer& l, int level, int x, int y) const;
  glm::vec4 bilinear(const Layer& l, int level, glm::vec2 uv) const;
  void group();
  static void addLevels(Layer& layer);
  std::vector<glm::ivec2> slotsOf(const std::vector<int>& layers) const;

  std::vector<Layer> layers_;
  std::vector<glm::ivec2> groupSize_;
  std::vector<int> groupLayers_;
  std::vector<int> materialLayer_, emissionLayer_;
};

}  // namespace mvr::shading
