#include "shading/lighting.h"

#include <cmath>
#include <string>

#include "mvr/error.h"
#include "mvr/gl/gl_program.h"
#include "mvr/parallel.h"
#include "shading/image_light.h"

namespace mvr::shading {

void applyExposure(Scene& scene, std::optional<float> ev) {
  if (!ev) {
    for (Light& light : scene.lights) light.color *= light.autoExposure;
    return;
  }
  const float k = std::exp2(*ev);
  for (Light& light : scene.lights) light.color *= k;
  scene.ambient *= k;
  if (scene.environment) scene.environment->intensity *= k;
  for (Material& m : scene.materials) m.emission *= k;
}

std::vector<glm::vec3> vertexAlbedo(const Scene& scene) {
  std::vector<glm::vec3> albedo(scene.colors);
  const std::vector<uint32_t> material = scene.vertexMaterials();
  for (size_t v = 0; v < albedo.size(); ++v) albedo[v] *= scene.materials[material[v]].diffuse;
  return albedo;
}

std::vector<float> vertexCullFlags(const Scene& scene) {
  std::vector<float> flags(scene.vertexCount(), 0.0f);
  for (size_t t = 0; t < scene.triangleCount(); ++t)
    if (!scene.materials[scene.materialIds[t]].twoSided)
      for (int k = 0; k < 3; ++k) flags[scene.triangles[t][k]] = 1.0f;
  return flags;
}

glm::vec3 towardsLight(const Light& light, const glm::vec3& p) {
  return light.positional() ? glm::normalize(light.vector - p) : -light.vector;
}

// Keep in step with the GLSL below.
glm::vec3 diffuse(const Scene& scene, const glm::vec3& albedo, const glm::vec3& p,
                  const glm::vec3& n) {
  glm::vec3 sum = scene.ambient + environmentDiffuse(scene, n);
  for (const Light& light : scene.lights) {
    const glm::vec3 l = towardsLight(light, p);
    sum += incidentLight(light, p, l) * glm::max(glm::dot(n, l), 0.0f);
  }
  return glm::clamp(albedo * sum, 0.0f, diffuseCeiling(scene));
}

float diffuseCeiling(const Scene& scene) { return scene.highDynamicRange ? 3.0e38f : 1.0f; }

glm::vec3 surfaceLight(const Scene& scene, const Material& m, const glm::vec3& albedo, const glm::vec3& p,
                       const glm::vec3& n) {
  return m.unlit ? albedo : diffuse(scene, albedo, p, n);
}

VertexColors litVertexColors(const Scene& scene) {
  std::vector<glm::vec3> albedo = vertexAlbedo(scene);
  VertexColors c;
  c.front.resize(scene.vertexCount());
  c.back.resize(scene.vertexCount());
  const std::vector<uint32_t> material = scene.vertexMaterials();
  // On the pool: a moving scene (a sequence, mvr live) is lit every frame.
  parallelChunks(scene.vertexCount(), 16384, [&](size_t begin, size_t end) {
    for (size_t v = begin; v < end; ++v) {
      // Unclamped sum: interpolated, it equals svr's lit colour plus the
      // material's emission per pixel. An emission texture's texels are
      // the texture pass's to add.
      const Material& m = scene.materials[material[v]];
      const glm::vec3 e = m.emissionTexture.empty() ? m.emission : glm::vec3(0.0f);
      c.front[v] = surfaceLight(scene, m, albedo[v], scene.positions[v], scene.normals[v]) + e;
      c.back[v] = surfaceLight(scene, m, albedo[v], scene.positions[v], -scene.normals[v]) + e;
    }
  });
  return c;
}

const std::string& glslLighting() {
  static const std::string src = std::string(glslEnvironmentDiffuse()) + R"(
uniform int uLightCount;
uniform vec4 uLightVector[8];  // w = 0: direction light travels; w = 1: position
uniform vec3 uLightColor[8];
uniform vec3 uLightAxis[8];  // a spot's
uniform vec2 uLightCone[8];  // scale, offset (coneScaleOffset): 0, 1 for no spot
uniform vec2 uLightFalloff[8];  // on (1) or off (0), 1 / range^2 (0: no range)
uniform vec3 uAmbient;
uniform float uDiffuseCeiling;  // 1, or no ceiling (Scene::highDynamicRange)

vec3 towardsLight(int i, vec3 p) {
  return uLightVector[i].w == 0.0 ? -uLightVector[i].xyz : normalize(uLightVector[i].xyz - p);
}

// uLightColor[i] times coneFactor and distanceFalloff (1 in a scene
// without spots or falloff lights): incidentLight.
vec3 lightColor(int i, vec3 p, vec3 l) {
  vec3 c = uLightColor[i];
#ifdef SPOT_LIGHTS
  float t = clamp(dot(uLightAxis[i], -l) * uLightCone[i].x + uLightCone[i].y, 0.0, 1.0);
  c *= t * t;
#endif
#ifdef FALLOFF_LIGHTS
  if (uLightFalloff[i].x != 0.0) {
    vec3 d = uLightVector[i].xyz - p;
    float d2 = max(dot(d, d), 0.01), q = d2 * uLightFalloff[i].y;
    c *= (uLightFalloff[i].y > 0.0 ? clamp(1.0 - q * q, 0.0, 1.0) : 1.0) / d2;
  }
#endif
  return c;
}

vec3 diffuseLight(vec3 albedo, vec3 p, vec3 n) {
  vec3 sum = uAmbient;
#ifdef ENVIRONMENT
  sum += environmentDiffuse(n);
#endif
  for (int i = 0; i < uLightCount; ++i) {
    vec3 l = towardsLight(i, p);
    sum += lightColor(i, p, l) * max(dot(n, l), 0.0);
  }
  return clamp(albedo * sum, 0.0, uDiffuseCeiling);
}
)";
  return src;
}

const char* glslSurfaceLight() {
  return R"(
vec3 surfaceLight(int material, vec3 albedo, vec3 p, vec3 n) {
  return materialUnlit(material) ? albedo : diffuseLight(albedo, p, n);
}
)";
}

void setLightUniforms(const gl::Program& program, const Scene& scene) {
  if (scene.lights.size() > size_t(kMaxLights))
    fail(scene.source, "more than " + std::to_string(kMaxLights) + " lights");
  gl::setUniform(program, "uLightCount", int(scene.lights.size()));
  gl::setUniform(program, "uAmbient", scene.ambient);
  gl::setUniform(program, "uDiffuseCeiling", diffuseCeiling(scene));
  setEnvironmentUniforms(program, scene);
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& l = scene.lights[i];
    const std::string idx = "[" + std::to_string(i) + "]";
    gl::setUniform(program, ("uLightVector" + idx).c_str(), glm::vec4(l.vector, l.positional() ? 1.0f : 0.0f));
    gl::setUniform(program, ("uLightColor" + idx).c_str(), l.color);
    gl::setUniform(program, ("uLightAxis" + idx).c_str(), l.axis);
    gl::setUniform(program, ("uLightCone" + idx).c_str(), coneScaleOffset(l));
    const float inverseRange2 = l.range > 0.0f ? 1.0f / (l.range * l.range) : 0.0f;
    gl::setUniform(program, ("uLightFalloff" + idx).c_str(), glm::vec2(l.falloff ? 1.0f : 0.0f, inverseRange2));
  }
}

}  // namespace mvr::shading
