#pragma once
// View-dependent shading (Halle 5.6.8, 6.5.4): per-pixel Phong or
// Blinn-Phong specular highlights from every light, for the eye of the view
// being drawn. In EPI space the eye follows the EPI row (the view) and the
// surface point and normal follow the slice parameter. One formula, written
// in C++ (CPU back end) and GLSL (every GL back end), side by side.
#include <string>

#include <glm/glm.hpp>

#include "mvr/gl/gl_handles.h"
#include "mvr/scene.h"
#include "shading/environment_set.h"
#include "shading/texture_set.h"

namespace mvr::shading {

// What the view-dependent pass adds and takes off at point p with normal n
// (any length) for the eye: the specular light leaving towards it, and
// (glTF's fresnel_mix) the diffuse light that a Ggx material's Fresnel
// term (its dielectric F0) reflects off instead, from every light and from
// the ambient and environment (their scattered share); the pass takes
// that off the view-independent diffuse, which is albedo times its light.
// Zero loss for other models. One pass over the lights for both.
struct ViewDependentLight {
  glm::vec3 specular{0.0f}, fresnelLoss{0.0f};
};
ViewDependentLight viewDependentLight(const Scene& scene, const Material& material, const glm::vec3& albedo,
                                      const glm::vec3& p, const glm::vec3& n, const glm::vec3& eye);

// Its specular light alone.
glm::vec3 specularLight(const Scene& scene, const Material& material, const glm::vec3& p,
                        const glm::vec3& n, const glm::vec3& eye);

// Its Fresnel loss alone (deferred's separate-highlights lighting pass).
glm::vec3 diffuseFresnelLoss(const Scene& scene, const Material& material, const glm::vec3& albedo,
                             const glm::vec3& p, const glm::vec3& n, const glm::vec3& eye);

// GLSL: the Materials storage block (binding 1) that makeMaterialBuffer
// fills; params.y of a material is its texture layer (-1 for none),
// reflectivity.w its texture group, glow.yz its emission texture's
// (TextureSet::glsl samples them); materialEmission(material) and
// materialUnlit(material) and hasEmissionTexture(material).
const char* glslMaterials();

// GLSL: glslMaterials() and
// `void viewDependentLight(int material, vec3 albedo, vec3 p, vec3 n, vec3 eye,
// out vec3 specular, out vec3 loss)`, and its loss alone, `vec3
// diffuseFresnelLoss(int material, vec3 albedo, vec3 p, vec3 n, vec3 eye)`
// (deferred's separate-highlights pass); needs
// glslLighting() before it for the light uniforms.
const std::string& glslSpecular();

// The scene's materials as the storage block glslSpecular() declares.
// Per material: its texture's and its emission texture's group and layer
// (TextureSet's slots; -1 for none), whether it is unlit, and its
// reflection map.
gl::Buffer makeMaterialBuffer(const Scene& scene, const TextureSet& textures,
                              const std::vector<EnvironmentSet::Map>& reflectionMaps);

}  // namespace mvr::shading
