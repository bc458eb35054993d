#include "shading/gpu_materials.h"

#include "shading/view_dependent.h"

namespace mvr::shading {

GpuMaterials::GpuMaterials(const Scene& scene, const TextureSet& textures, bool uploadTextures)
    : materials_(makeMaterialBuffer(scene, textures.materialLayers())) {
  if (uploadTextures && !textures.empty()) textures_ = textures.upload();
}

void GpuMaterials::bind(GLuint textureUnit) const {
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, materials_.id());
  if (textures_.id()) gl::BindTextureUnit(textureUnit, textures_.id());
}

}  // namespace mvr::shading
