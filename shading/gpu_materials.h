#pragma once
// The scene's materials as every GL back end reads them: the Materials
// storage block that glslSpecular() declares (binding 1), carrying each
// material's texture layer and reflection map, the textures as one
// mipmapped 2D array, and the reflection maps (EnvironmentSet's units).
#include "mvr/gl/gl_handles.h"
#include "mvr/scene.h"
#include "shading/environment_set.h"
#include "shading/texture_set.h"

namespace mvr::shading {

class GpuMaterials {
 public:
  // uploadTextures = false: the layers only (paths that never sample the
  // 2D array, such as MVR's texture vectors).
  GpuMaterials(const Scene& scene, const TextureSet& textures, const EnvironmentSet& environment,
               bool uploadTextures = true);
  // The storage block at binding 1, the texture array (if uploaded) at
  // textureUnit and the reflection maps.
  void bind(GLuint textureUnit) const;

 private:
  gl::Buffer materials_;
  gl::Texture textures_, cubeMaps_, sphereMaps_;
};

}  // namespace mvr::shading
