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

namespace {

// Phong and Blinn-Phong: the highlight from every light, for unit n and v.
glm::vec3 phongLight(const Scene& scene, const Material& m, const glm::vec3& p, const glm::vec3& n,
                     const glm::vec3& v) {
  glm::vec3 sum(0.0f);
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

}  // namespace

// Keep in step with the GLSL below. One pass over the lights gives a Ggx
// material's lobe and its Fresnel loss: the direction, the light reaching
// p and the irradiance are found once.
ViewDependentLight viewDependentLight(const Scene& scene, const Material& m, const glm::vec3& albedo,
                                      const glm::vec3& p, const glm::vec3& nIn, const glm::vec3& eye) {
  const float len = glm::length(nIn), dist = glm::length(eye - p);
  if (!(len > 1e-20f) || !(dist > 1e-20f)) return {};
  const glm::vec3 n = nIn / len, v = (eye - p) / dist;
  const bool lobe = m.specular != glm::vec3(0.0f);
  if (m.specularModel != SpecularModel::Ggx) return {lobe ? phongLight(scene, m, p, n, v) : glm::vec3(0.0f), {}};
  const bool loses = !m.unlit;
  const float nv = glm::dot(n, v);
  const glm::vec3 irradiance = environmentDiffuse(scene, n);
  const glm::vec2 e = dfg(m.roughness, nv);  // the table, read once for the three uses below
  glm::vec3 specular(0.0f), lost(0.0f);
  if (loses) lost = (scene.ambient + irradiance) * scatteredShare(m.dielectricF0, m.specularF90, e);
  for (const Light& light : scene.lights) {
    const glm::vec3 l = towardsLight(light, p), c = incidentLight(light, p, l);
    if (lobe) specular += c * ggxLobe(m.specular, m.specularF90, m.roughness, n, l, v);
    const float nl = glm::dot(n, l);
    if (loses && nl > 0.0f)
      lost += c * nl * schlickFresnel(m.dielectricF0, m.specularF90, glm::dot(v, glm::normalize(l + v)));
  }
  if (lobe)
    specular = specular * multiScatterCompensation(m.specular, e) +
               environmentSpecular(scene, m, n, v, irradiance, splitScattering(m.specular, m.specularF90, e));
  return {specular, albedo * lost};
}

glm::vec3 specularLight(const Scene& scene, const Material& m, const glm::vec3& p, const glm::vec3& n,
                        const glm::vec3& eye) {
  return viewDependentLight(scene, m, glm::vec3(0.0f), p, n, eye).specular;
}

glm::vec3 diffuseFresnelLoss(const Scene& scene, const Material& m, const glm::vec3& albedo, const glm::vec3& p,
                             const glm::vec3& n, const glm::vec3& eye) {
  return viewDependentLight(scene, m, albedo, p, n, eye).fresnelLoss;
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
vec3 environmentSpecular(Material m, vec3 n, vec3 v, vec3 irradiance, vec2 e) {
  float roughness = clamp(m.specular.w, kMinRoughness, 1.0), a2 = roughness * roughness * roughness * roughness;
  vec3 r = normalize(mix(reflect(-v, n), n, a2));
  vec3 single, multiple;
  splitScattering(m.specular.rgb, m.glow.w, e, single, multiple);
  return environmentRadiance(r, roughness) * single + irradiance * multiple;
}
#endif

vec3 phongLight(Material m, vec3 p, vec3 n, vec3 v) {
  vec3 sum = vec3(0.0);
  for (int i = 0; i < uLightCount; ++i) {
    vec3 l = towardsLight(i, p);
    if (dot(n, l) <= 0.0) continue;
    float s = m.params.x == 0.0 ? dot(reflect(-l, n), v) : dot(n, normalize(l + v));
    sum += lightColor(i, p, l) * pow(max(s, 1e-30), m.specular.w);
  }
  return m.specular.rgb * sum;
}

void viewDependentLight(int material, vec3 albedo, vec3 p, vec3 nIn, vec3 eye, out vec3 specular, out vec3 loss) {
  Material m = uMaterials[material];
  specular = vec3(0.0);
  loss = vec3(0.0);
  float len = length(nIn), dist = length(eye - p);
  if (!(len > 1e-20) || !(dist > 1e-20)) return;
  vec3 n = nIn / len, v = (eye - p) / dist;
  bool lobe = m.specular.rgb != vec3(0.0);
  if (m.params.x != 2.0) {
    if (lobe) specular = phongLight(m, p, n, v);
    return;
  }
  bool loses = m.glow.x == 0.0;
  float nv = dot(n, v);
  vec3 irradiance = vec3(0.0);
#ifdef ENVIRONMENT
  irradiance = environmentDiffuse(n);
#endif
  vec2 e = dfg(m.specular.w, nv);  // the table, read once for the three uses below
  vec3 lost = vec3(0.0);
  if (loses) lost = (uAmbient + irradiance) * scatteredShare(m.dielectric.rgb, m.glow.w, e);
  for (int i = 0; i < uLightCount; ++i) {
    vec3 l = towardsLight(i, p), c = lightColor(i, p, l);
    if (lobe) specular += c * ggxLobe(m.specular.rgb, m.glow.w, m.specular.w, n, l, v);
    float nl = dot(n, l);
    if (loses && nl > 0.0) lost += c * nl * schlickFresnel(m.dielectric.rgb, m.glow.w, dot(v, normalize(l + v)));
  }
  if (lobe) {
    specular *= multiScatterCompensation(m.specular.rgb, e);
#ifdef ENVIRONMENT
    specular += environmentSpecular(m, n, v, irradiance, e);
#endif
  }
  loss = albedo * lost;
}

vec3 diffuseFresnelLoss(int material, vec3 albedo, vec3 p, vec3 n, vec3 eye) {
  vec3 specular, loss;
  viewDependentLight(material, albedo, p, n, eye, specular, loss);
  return loss;
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
