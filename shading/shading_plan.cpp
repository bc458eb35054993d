#include "shading/shading_plan.h"

#include "shading/lighting.h"

namespace mvr::shading {

ShadingPlan planShading(const Scene& scene) {
  ShadingPlan plan;
  for (const Material& m : scene.materials) {
    plan.texture |= !m.texture.empty() || !m.emissionTexture.empty();
    plan.emissionTexture |= !m.emissionTexture.empty();
    plan.specular |= m.specular != glm::vec3(0.0f);
    plan.reflection |= !m.reflectionMap.empty();
    plan.emission |= m.emission != glm::vec3(0.0f) || !m.emissionTexture.empty();
    plan.mask |= m.masked();
    plan.ggx |= m.specularModel == SpecularModel::Ggx && !m.unlit && m.specular != glm::vec3(0.0f);
  }
  plan.environment = scene.environment.has_value();
  for (const Light& l : scene.lights) {
    plan.spots |= l.type == Light::Type::Spot;
    plan.falloff |= l.falloff;
  }
  if (plan.texture) {
    plan.uv = plan.extraCount;
    plan.extraCount += 2;
  }
  if (plan.specular || plan.reflection) {
    plan.position = plan.extraCount;
    plan.normal = plan.extraCount + 3;
    plan.extraCount += 6;
  }
  if (plan.ggx) {  // a Ggx material with an F0 is specular: position and normal are there
    plan.albedo = plan.extraCount;
    plan.extraCount += 3;
  }
  if (plan.reflection) {
    plan.reflect = plan.extraCount;
    plan.extraCount += 9;
  }
  return plan;
}

std::vector<Pass> ShadingPlan::passes() const {
  std::vector<Pass> p{Pass::Diffuse};
  if (texture) p.push_back(Pass::Texture);
  if (specular || reflection) p.push_back(Pass::ViewDependent);
  return p;
}

const char* passName(Pass pass) {
  switch (pass) {
    case Pass::Diffuse: return "diffuse";
    case Pass::Texture: return "texture";
    case Pass::ViewDependent: return "view-dependent";
  }
  return "?";
}

std::string ShadingPlan::glslDefines() const {
  std::string s;
  for (Pass p : passes()) {
    if (p == Pass::Texture) s += "#define TEXTURE\n";
    if (p == Pass::ViewDependent) s += "#define VIEW_DEPENDENT\n";
  }
  if (reflection) s += "#define REFLECT\n";
  if (emission) s += "#define EMISSION\n";
  if (emissionTexture) s += "#define EMISSION_TEXTURE\n";
  if (mask) s += "#define MASK\n";
  if (spots) s += "#define SPOT_LIGHTS\n";
  if (falloff) s += "#define FALLOFF_LIGHTS\n";
  if (albedo >= 0) s += "#define GGX\n";
  if (environment) s += "#define ENVIRONMENT\n";
  return s;
}

std::string ShadingPlan::passNames() const {
  std::string s;
  for (Pass p : passes()) s += (s.empty() ? "" : "+") + std::string(passName(p));
  return s;
}

}  // namespace mvr::shading

namespace mvr::shading {

std::vector<float> vertexExtras(const Scene& scene, const ShadingPlan& plan) {
  const int k = plan.extraCount;
  std::vector<float> out(scene.vertexCount() * size_t(k));
  const std::vector<glm::vec3> albedo = plan.albedo >= 0 ? vertexAlbedo(scene) : std::vector<glm::vec3>{};
  for (size_t v = 0; v < scene.vertexCount(); ++v) {
    float* e = out.data() + v * k;
    if (plan.uv >= 0 && !scene.uvs.empty()) {
      e[plan.uv] = scene.uvs[v].x;
      e[plan.uv + 1] = scene.uvs[v].y;
    }
    const glm::vec3 p = scene.positions[v], n = scene.normals[v];
    if (plan.position >= 0)
      for (int c = 0; c < 3; ++c) e[plan.position + c] = p[c], e[plan.normal + c] = n[c];
    if (plan.albedo >= 0)
      for (int c = 0; c < 3; ++c) e[plan.albedo + c] = albedo[v][c];
    if (plan.reflect >= 0) {
      const glm::vec3 a = p - 2.0f * glm::dot(n, p) * n;
      const float m[9] = {a.x, a.y, a.z, 2 * n.x * n.x - 1, 2 * n.y * n.y - 1, 2 * n.z * n.z - 1,
                          2 * n.x * n.y, 2 * n.x * n.z, 2 * n.y * n.z};
      for (int c = 0; c < 9; ++c) e[plan.reflect + c] = m[c];
    }
  }
  return out;
}

}  // namespace mvr::shading
