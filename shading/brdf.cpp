#include "shading/brdf.h"

#include <algorithm>
#include <cmath>

namespace mvr::shading {

// Keep in step with the GLSL below.
float ggxDistribution(float alpha, float nh) { return ggxDistribution(alpha, nh, 1.0f - nh * nh); }

// 1 + nh^2 (a2 - 1) as sin^2 + (nh alpha)^2: near a mirror the former
// loses all of a2 ~ 1e-5 to rounding in float (Filament's form).
float ggxDistribution(float alpha, float nh, float sin2) {
  const float a = nh * alpha, d = sin2 + a * a;
  return alpha * alpha / (float(M_PI) * d * d);
}

float smithVisibility(float alpha, float nl, float nv) {
  const float a2 = alpha * alpha;
  const float gv = nl * std::sqrt(a2 + (1.0f - a2) * nv * nv);
  const float gl = nv * std::sqrt(a2 + (1.0f - a2) * nl * nl);
  return 0.5f / std::max(gv + gl, 1e-6f);
}

glm::vec3 schlickFresnel(const glm::vec3& f0, float f90, float vh) {
  const float x = 1.0f - std::clamp(vh, 0.0f, 1.0f), x2 = x * x;
  return f0 + (glm::vec3(f90) - f0) * (x2 * x2 * x);
}

glm::vec3 ggxLobe(const glm::vec3& f0, float f90, float roughness, const glm::vec3& n,
                  const glm::vec3& l, const glm::vec3& v) {
  const float nl = glm::dot(n, l), nv = glm::dot(n, v);
  if (nl <= 0.0f || nv <= 0.0f) return glm::vec3(0.0f);
  const glm::vec3 h = glm::normalize(l + v);
  const float r = std::clamp(roughness, kMinRoughness, 1.0f), alpha = r * r;
  const float nh = std::clamp(glm::dot(n, h), 0.0f, 1.0f), sin2 = glm::dot(glm::cross(n, h), glm::cross(n, h));
  return schlickFresnel(f0, f90, glm::dot(v, h)) *
         (float(M_PI) * nl * smithVisibility(alpha, nl, nv) * ggxDistribution(alpha, nh, sin2));
}

float ggxBlinnExponent(float roughness) {
  const float r = std::clamp(roughness, kMinRoughness, 1.0f), alpha = r * r;
  return std::max(2.0f / (alpha * alpha) - 2.0f, 0.0f);
}

const char* glslBrdf() {
  return R"(
const float kMinRoughness = 0.0525;
float ggxDistribution(float alpha, float nh, float sin2) {
  float a = nh * alpha, d = sin2 + a * a;
  return alpha * alpha / (3.14159265 * d * d);
}
float smithVisibility(float alpha, float nl, float nv) {
  float a2 = alpha * alpha;
  float gv = nl * sqrt(a2 + (1.0 - a2) * nv * nv);
  float gl = nv * sqrt(a2 + (1.0 - a2) * nl * nl);
  return 0.5 / max(gv + gl, 1e-6);
}
vec3 schlickFresnel(vec3 f0, float f90, float vh) {
  float x = 1.0 - clamp(vh, 0.0, 1.0), x2 = x * x;
  return f0 + (vec3(f90) - f0) * (x2 * x2 * x);
}
vec3 ggxLobe(vec3 f0, float f90, float roughness, vec3 n, vec3 l, vec3 v) {
  float nl = dot(n, l), nv = dot(n, v);
  if (nl <= 0.0 || nv <= 0.0) return vec3(0.0);
  vec3 h = normalize(l + v);
  float r = clamp(roughness, kMinRoughness, 1.0), alpha = r * r;
  vec3 nxh = cross(n, h);
  float nh = clamp(dot(n, h), 0.0, 1.0);
  return schlickFresnel(f0, f90, dot(v, h)) *
         (3.14159265 * nl * smithVisibility(alpha, nl, nv) * ggxDistribution(alpha, nh, dot(nxh, nxh)));
}
)";
}

}  // namespace mvr::shading
