#pragma once
// The scene's materials as every GL back end reads them: the Materials
// storage block that glslSpecular() declares (binding 1), carrying each
// material's texture layer, and the textures as one mipmapped 2D array.
#include "mvr/gl_handles.h"
#include "mvr/scene.h"
#include "shading/texture_set.h"

namespace mvr::shading {

class GpuMaterials {
 public:
  // uploadTextures = false: the layers only (paths that never sample the
  // 2D array, such as MVR's texture vectors).
  GpuMaterials(const Scene& scene, const TextureSet& textures, bool uploadTextures = true);
  // The storage block at binding 1 and, if uploaded, the array at textureUnit.
  void bind(GLuint textureUnit) const;

 private:
  gl::Buffer materials_;
  gl::Texture textures_;
};

}  // namespace mvr::shading
