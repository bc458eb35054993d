#pragma once
// The scene's materials as every GL back end reads them: the Materials
// storage block that glslSpecular() declares (binding 1), carrying each
// material's texture group, layer and reflection map, the textures as
// mipmapped 2D arrays (TextureSet's units), and the reflection maps
// (EnvironmentSet's units).
#include <vector>

#include "mvr/gl/gl_handles.h"
#include "mvr/scene.h"
#include "shading/environment_set.h"
#include "shading/texture_set.h"

namespace mvr::shading {

class GpuMaterials {
 public:
  // uploadTextures = false: the layers only (paths that never sample the
  // 2D arrays, such as MVR's texture vectors).
  GpuMaterials(const Scene& scene, const TextureSet& textures, const EnvironmentSet& environment,
               bool uploadTextures = true);
  // The storage block at binding 1, the texture groups (if uploaded) and
  // the reflection maps, each at its unit.
  void bind() const;

 private:
  gl::Buffer materials_;
  std::vector<gl::Texture> textures_;
  gl::Texture cubeMaps_, sphereMaps_;
  gl::Texture environment_;  // the image-based light's levels (ImageLight), if the scene has one
};

}  // namespace mvr::shading
