#include "shading/gpu_materials.h"

#include "shading/view_dependent.h"

namespace mvr::shading {

GpuMaterials::GpuMaterials(const Scene& scene, const TextureSet& textures,
                           const EnvironmentSet& environment, bool uploadTextures)
    : materials_(makeMaterialBuffer(scene, textures.materialLayers(), environment.materialMaps())),
      cubeMaps_(environment.uploadCubes()),
      sphereMaps_(environment.uploadSpheres()) {
  if (uploadTextures && !textures.empty()) textures_ = textures.upload();
}

void GpuMaterials::bind(GLuint textureUnit) const {
  gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, materials_.id());
  if (textures_.id()) gl::BindTextureUnit(textureUnit, textures_.id());
  if (cubeMaps_.id()) gl::BindTextureUnit(EnvironmentSet::kCubeUnit, cubeMaps_.id());
  if (sphereMaps_.id()) gl::BindTextureUnit(EnvironmentSet::kSphereUnit, sphereMaps_.id());
}

}  // namespace mvr::shading
