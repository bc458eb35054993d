#include "shading/view_dependent.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "shading/brdf.h"
#include "shading/image_light.h"
#include "shading/lighting.h"

namespace mvr::shading {
namespace {

// std430 layout of one material in the storage block.
struct GpuMaterial {
  glm::vec4 specular;  // rgb (Ggx: F0), shininess (Ggx: roughness)
  glm::vec4 params;    // model (0 Phong, 1 Blinn-Phong, 2 Ggx), texture layer, reflection layer, map kind
  glm::vec4 reflectivity;  // rgb, texture group
  glm::vec4 emission;      // rgb, alpha cut-off (0: opaque)
  glm::vec4 glow;          // unlit (1) or lit (0), emission texture group, layer (-1: none), Ggx's F90
  glm::vec4 dielectric;    // Ggx: the dielectric's F0, 0
};

float modelCode(SpecularModel model) {
  return model == SpecularModel::Phong ? 0.0f : model == SpecularModel::BlinnPhong ? 1.0f : 2.0f;
}

}  // namespace

// Keep in step with the GLSL below.
glm::vec3 specularLight(const Scene& scene, const Material& m, const glm::vec3& p,
                        const glm::vec3& nIn, const glm::vec3& eye) {
  const float len = glm::length(nIn), dist = glm::length(eye - p);
  if (m.specular == glm::vec3(0.0f) || !(len > 1e-20f) || !(dist > 1e-20f)) return glm::vec3(0.0f);
  const glm::vec3 n = nIn / len, v = (eye - p) / dist;
  glm::vec3 sum(0.0f);
  if (m.specularModel == SpecularModel::Ggx) {
    for (const Light& light : scene.lights) {
      const glm::vec3 l = towardsLight(light, p);
      sum += incidentLight(light, p, l) * ggxLobe(m.specular, m.specularF90, m.roughness, n, l, v);
    }
    return sum * multiScatterCompensation(m.specular, m.roughness, glm::dot(n, v)) + environmentSpecular(scene, m, n, v);
  }
  for (const Light& light : scene.lights) {
    const glm::vec3 l = towardsLight(light, p);
    if (glm::dot(n, l) <= 0.0f) continue;
    const float s = m.specularModel == SpecularModel::Phong
                        ? glm::dot(glm::reflect(-l, n), v)
                        : glm::dot(n, glm::normalize(l + v));
    sum += incidentLight(light, p, l) * std::pow(std::max(s, 1e-30f), m.shininess);
  }
  return m.specular * sum;
}

// Keep in step with the GLSL below.
glm::vec3 diffuseFresnelLoss(const Scene& scene, const Material& m, const glm::vec3& albedo, const glm::vec3& p,
                             const glm::vec3& nIn, const glm::vec3& eye) {
  const float len = glm::length(nIn), dist = glm::length(eye - p);
  if (m.specularModel != SpecularModel::Ggx || m.unlit || !(len > 1e-20f) || !(dist > 1e-20f)) return glm::vec3(0.0f);
  const glm::vec3 n = nIn / len, v = (eye - p) / dist;
  glm::vec3 sum = (scene.ambient + environmentDiffuse(scene, n)) * scatteredShare(m.dielectricF0, m.specularF90, m.roughness, glm::dot(n, v));
  for (const Light& light : scene.lights) {
    const glm::vec3 l = towardsLight(light, p);
    const float nl = glm::dot(n, l);
    if (nl <= 0.0f) continue;
    sum += incidentLight(light, p, l) * nl * schlickFresnel(m.dielectricF0, m.specularF90, glm::dot(v, glm::normalize(l + v)));
  }
  return albedo * sum;
}

const char* glslMaterials() {
  return R"(
struct Material {
  vec4 specular;  // rgb (Ggx: F0), shininess (Ggx: roughness)
  vec4 params;    // model (0 Phong, 1 Blinn-Phong, 2 Ggx), texture layer, reflection layer, map kind
  vec4 reflectivity;  // rgb, texture group (TextureSet::glsl)
  vec4 emission;      // rgb, alpha cut-off (0: opaque)
  vec4 glow;          // unlit (1) or lit (0), emission texture group, layer (-1: none), Ggx's F90
  vec4 dielectric;    // Ggx: the dielectric's F0, 0
};
// Opened by the split-sum table (shading/brdf.h, kDfgSize^2 cells).
layout(std430, binding = 1) readonly buffer Materials { vec2 uDfg[256]; Material uMaterials[]; };
vec3 materialEmission(int material) { return uMaterials[material].emission.rgb; }
bool materialUnlit(int material) { return uMaterials[material].glow.x != 0.0; }
bool hasEmissionTexture(int material) { return uMaterials[material].glow.z >= 0.0; }
// A cut-out's texel below its cut-off: the surface is not there.
bool maskedOut(int material, float alpha) { return alpha < uMaterials[material].emission.w; }
)";
}

const std::string& glslSpecular() {
  static const std::string src = std::string(glslMaterials()) + glslBrdf() + glslEnvironmentRadiance() + R"(

#ifdef ENVIRONMENT
// environmentSpecular in C++ (shading/image_light.h).
vec3 environmentSpecular(Material m, vec3 n, vec3 v) {
  float roughness = clamp(m.specular.w, kMinRoughness, 1.0), a2 = roughness * roughness * roughness * roughness;
  vec3 r = normalize(mix(reflect(-v, n), n, a2));
  vec3 single, multiple;
  splitScattering(m.specular.rgb, m.glow.w, roughness, dot(n, v), single, multiple);
  return environmentRadiance(r, roughness) * single + environmentDiffuse(n) * multiple;
}
#endif

vec3 specularLight(int material, vec3 p, vec3 nIn, vec3 eye) {
  Material m = uMaterials[material];
  float len = length(nIn), dist = length(eye - p);
  if (m.specular.rgb == vec3(0.0) || !(len > 1e-20) || !(dist > 1e-20)) return vec3(0.0);
  vec3 n = nIn / len, v = (eye - p) / dist;
  vec3 sum = vec3(0.0);
  if (m.params.x == 2.0) {
    for (int i = 0; i < uLightCount; ++i) {
      vec3 l = towardsLight(i, p);
      sum += lightColor(i, p, l) * ggxLobe(m.specular.rgb, m.glow.w, m.specular.w, n, l, v);
    }
    sum *= multiScatterCompensation(m.specular.rgb, m.specular.w, dot(n, v));
#ifdef ENVIRONMENT
    sum += environmentSpecular(m, n, v);
#endif
    return sum;
  }
  for (int i = 0; i < uLightCount; ++i) {
    vec3 l = towardsLight(i, p);
    if (dot(n, l) <= 0.0) continue;
    float s = m.params.x == 0.0 ? dot(reflect(-l, n), v) : dot(n, normalize(l + v));
    sum += lightColor(i, p, l) * pow(max(s, 1e-30), m.specular.w);
  }
  return m.specular.rgb * sum;
}

vec3 diffuseFresnelLoss(int material, vec3 albedo, vec3 p, vec3 nIn, vec3 eye) {
  Material m = uMaterials[material];
  float len = length(nIn), dist = length(eye - p);
  if (m.params.x != 2.0 || m.glow.x != 0.0 || !(len > 1e-20) || !(dist > 1e-20)) return vec3(0.0);
  vec3 n = nIn / len, v = (eye - p) / dist;
  vec3 sum = uAmbient;
#ifdef ENVIRONMENT
  sum += environmentDiffuse(n);
#endif
  sum *= scatteredShare(m.dielectric.rgb, m.glow.w, m.specular.w, dot(n, v));
  for (int i = 0; i < uLightCount; ++i) {
    vec3 l = towardsLight(i, p);
    float nl = dot(n, l);
    if (nl <= 0.0) continue;
    sum += lightColor(i, p, l) * nl * schlickFresnel(m.dielectric.rgb, m.glow.w, dot(v, normalize(l + v)));
  }
  return albedo * sum;
}
)";
  return src;
}

gl::Buffer makeMaterialBuffer(const Scene& scene, const TextureSet& textures,
                              const std::vector<EnvironmentSet::Map>& reflectionMaps) {
  std::vector<GpuMaterial> gpu;
  const std::vector<glm::ivec2> textureSlots = textures.materialSlots(), emissionSlots = textures.emissionSlots();
  for (size_t i = 0; i < scene.materials.size(); ++i) {
    const Material& m = scene.materials[i];
    const glm::ivec2 slot = i < textureSlots.size() ? textureSlots[i] : glm::ivec2(-1);
    const glm::ivec2 glow = i < emissionSlots.size() ? emissionSlots[i] : glm::ivec2(-1);
    const EnvironmentSet::Map map = i < reflectionMaps.size() ? reflectionMaps[i] : EnvironmentSet::Map{};
    const bool ggx = m.specularModel == SpecularModel::Ggx;
    gpu.push_back({glm::vec4(m.specular, ggx ? m.roughness : m.shininess),
                   glm::vec4(modelCode(m.specularModel), float(slot.y),
                             float(map.layer), float(map.kind)),
                   glm::vec4(m.reflectivity, float(std::max(slot.x, 0))), glm::vec4(m.emission, m.masked() ? m.alphaCutoff : 0.0f),
                   glm::vec4(m.unlit ? 1.0f : 0.0f, float(std::max(glow.x, 0)), float(glow.y), m.specularF90),
                   glm::vec4(m.dielectricF0, 0.0f)});
  }
  // The table first (256 vec2: 2048 bytes, a multiple of the materials' 16-byte alignment).
  static_assert(kDfgSize == 16, "the GLSL reads a 16 x 16 table");
  const std::vector<glm::vec2>& table = dfgTable();
  std::vector<glm::vec4> words(table.size() / 2 + gpu.size() * (sizeof(GpuMaterial) / sizeof(glm::vec4)));
  std::memcpy(words.data(), table.data(), table.size() * sizeof(glm::vec2));
  if (!gpu.empty()) std::memcpy(&words[table.size() / 2], gpu.data(), gpu.size() * sizeof(GpuMaterial));
  return gl::makeBuffer(words.data(), words.size());
}

}  // namespace mvr::shading
