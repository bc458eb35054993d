#pragma once
// View-independent lighting (ambient + Lambert diffuse over point and
// directional lights), shared by every back end: once per vertex on the CPU
// for MVR, per vertex per view in SVR's vertex shader, per pixel in the
// deferred pipeline. One formula, written twice (C++ and GLSL) side by side.
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "mvr/gl/gl_handles.h"
#include "mvr/scene.h"

namespace mvr::shading {

using mvr::kMaxLights;

// A camera's exposure (`--exposure`): with a value EV, every light, the
// ambient light and every emission are multiplied by 2^EV (the scene's
// radiance, exposed); without one (auto), the lights alone by their
// autoExposure.
void applyExposure(Scene& scene, std::optional<float> ev);

// Per vertex: material diffuse times vertex colour.
std::vector<glm::vec3> vertexAlbedo(const Scene& scene);
// Per vertex: 1 where the vertex's material culls back faces, else 0.
std::vector<float> vertexCullFlags(const Scene& scene);

// Unit vector from p towards the light.
glm::vec3 towardsLight(const Light& light, const glm::vec3& p);

glm::vec3 diffuse(const Scene& scene, const glm::vec3& albedo, const glm::vec3& position,
                  const glm::vec3& normal);

// Where diffuse() clamps the lit colour: 1, or (HDR) nowhere.
float diffuseCeiling(const Scene& scene);

// diffuse(), or the albedo itself where the material is unlit.
glm::vec3 surfaceLight(const Scene& scene, const Material& material, const glm::vec3& albedo,
                       const glm::vec3& position, const glm::vec3& normal);

// Front and back colours per vertex (back: normal flipped, two-sided),
// the material's emission included (MVR's diffuse pass) unless it has an
// emission texture, whose texels the texture pass adds.
struct VertexColors {
  std::vector<glm::vec3> front, back;
};
VertexColors litVertexColors(const Scene& scene);

// GLSL: uniforms and `vec3 diffuseLight(vec3 albedo, vec3 p, vec3 n)`; spot
// lights need SPOT_LIGHTS defined before it (ShadingPlan::glslDefines).
const std::string& glslLighting();
// GLSL after glslLighting() and glslMaterials(): `vec3 surfaceLight(int
// material, vec3 albedo, vec3 p, vec3 n)`, as the C++ one.
const char* glslSurfaceLight();
// Sets the uniforms glslLighting() declares; throws if too many lights.
void setLightUniforms(const gl::Program& program, const Scene& scene);

}  // namespace mvr::shading
