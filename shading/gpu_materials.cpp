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
  materials_.bindStorage(1);
  if (textures_.id()) textures_.bind(textureUnit);
  if (cubeMaps_.id()) cubeMaps_.bind(EnvironmentSet::kCubeUnit);
  if (sphereMaps_.id()) sphereMaps_.bind(EnvironmentSet::kSphereUnit);
}

}  // namespace mvr::shading
