#include "shading/gpu_materials.h"

#include "shading/image_light.h"
#include "shading/view_dependent.h"

namespace mvr::shading {

GpuMaterials::GpuMaterials(const Scene& scene, const TextureSet& textures,
                           const EnvironmentSet& environment, bool uploadTextures)
    : materials_(makeMaterialBuffer(scene, textures, environment.materialMaps())),
      cubeMaps_(environment.uploadCubes()),
      sphereMaps_(environment.uploadSpheres()) {
  if (uploadTextures && !textures.empty()) textures_ = textures.upload();
  if (scene.environment && scene.environment->light) environment_ = scene.environment->light->upload();
}

void GpuMaterials::bind() const {
  materials_.bindStorage(1);
  for (size_t g = 0; g < textures_.size(); ++g) textures_[g].bind(TextureSet::kFirstUnit + GLuint(g));
  if (cubeMaps_.id()) cubeMaps_.bind(EnvironmentSet::kCubeUnit);
  if (sphereMaps_.id()) sphereMaps_.bind(EnvironmentSet::kSphereUnit);
  if (environment_.id()) environment_.bind(kEnvironmentUnit);
}

}  // namespace mvr::shading
