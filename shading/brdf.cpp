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

glm::vec2 hammersley(uint32_t i, uint32_t n) {
  uint32_t bits = i;  // the radical inverse in base 2
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return {(float(i) + 0.5f) / float(n), float(bits) * 2.3283064e-10f};
}

glm::vec3 ggxHalfVector(const glm::vec2& xi, float alpha) {
  const float a2 = alpha * alpha, phi = 2.0f * float(M_PI) * xi.x;
  const float cosTheta = std::sqrt((1.0f - xi.y) / (1.0f + (a2 - 1.0f) * xi.y));
  const float sinTheta = std::sqrt(std::max(1.0f - cosTheta * cosTheta, 0.0f));
  return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

namespace {

// The cell at roughness r and n.v = mu: A and B by importance sampling
// GGX's D (n.h) over a Hammersley set, with the height-correlated Smith
// visibility: G V.h / (n.h n.v) = 4 V (n.l) (v.h) / (n.h).
glm::vec2 integrateDfg(float roughness, float mu) {
  constexpr int kSamples = 1024;
  const float alpha = roughness * roughness;
  const glm::vec3 v(std::sqrt(std::max(1.0f - mu * mu, 0.0f)), 0.0f, mu);
  glm::dvec2 sum(0.0);
  for (uint32_t i = 0; i < kSamples; ++i) {
    const glm::vec3 h = ggxHalfVector(hammersley(i, kSamples), alpha);
    const float vh = glm::dot(v, h);
    const glm::vec3 l = 2.0f * vh * h - v;
    if (l.z <= 0.0f || vh <= 0.0f) continue;
    const float g = 4.0f * smithVisibility(alpha, l.z, mu) * l.z * vh / h.z;
    const float fc = std::pow(1.0f - vh, 5.0f);
    sum += glm::dvec2((1.0f - fc) * g, fc * g);
  }
  return glm::vec2(sum / double(kSamples));
}

}  // namespace

const std::vector<glm::vec2>& dfgTable() {
  static const std::vector<glm::vec2> table = [] {
    std::vector<glm::vec2> t(kDfgSize * kDfgSize);
    for (int j = 0; j < kDfgSize; ++j)
      for (int i = 0; i < kDfgSize; ++i)
        t[size_t(j * kDfgSize + i)] = integrateDfg((float(i) + 0.5f) / kDfgSize, (float(j) + 0.5f) / kDfgSize);
    return t;
  }();
  return table;
}

// Keep in step with the GLSL below.
glm::vec2 dfg(float roughness, float nv) {
  const std::vector<glm::vec2>& t = dfgTable();
  const float r = std::clamp(roughness, kMinRoughness, 1.0f), mu = std::clamp(nv, 0.0f, 1.0f);
  const float x = std::clamp(r * kDfgSize - 0.5f, 0.0f, kDfgSize - 1.0f);
  const float y = std::clamp(mu * kDfgSize - 0.5f, 0.0f, kDfgSize - 1.0f);
  const int x0 = std::min(int(x), kDfgSize - 2), y0 = std::min(int(y), kDfgSize - 2);
  const float fx = x - float(x0), fy = y - float(y0);
  auto at = [&](int i, int j) { return t[size_t(j * kDfgSize + i)]; };
  return glm::mix(glm::mix(at(x0, y0), at(x0 + 1, y0), fx), glm::mix(at(x0, y0 + 1), at(x0 + 1, y0 + 1), fx), fy);
}

glm::vec3 multiScatterCompensation(const glm::vec3& f0, float roughness, float nv) {
  return multiScatterCompensation(f0, dfg(roughness, nv));
}

glm::vec3 multiScatterCompensation(const glm::vec3& f0, const glm::vec2& e) {
  return 1.0f + f0 * (1.0f / std::max(e.x + e.y, 1e-3f) - 1.0f);
}

Scattering splitScattering(const glm::vec3& f0, float f90, const glm::vec2& e) {
  const glm::vec3 single = f0 * e.x + f90 * e.y;
  const float lost = 1.0f - e.x - e.y;
  const glm::vec3 average = f0 + (1.0f - f0) * (1.0f / 21.0f);
  return {single, single * average / (1.0f - lost * average) * lost};
}

glm::vec3 scatteredShare(const glm::vec3& f0, float f90, const glm::vec2& e) {
  const Scattering s = splitScattering(f0, f90, e);
  return s.single + s.multiple;
}

float ggxBlinnExponent(float roughness) {
  const float r = std::clamp(roughness, kMinRoughness, 1.0f), alpha = r * r;
  return std::max(2.0f / (alpha * alpha) - 2.0f, 0.0f);
}

const char* glslBrdf() {
  return R"(
const float kMinRoughness = 0.045;
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
vec2 dfgAt(int i, int j) { return uDfg[j * 16 + i]; }
vec2 dfg(float roughness, float nv) {
  float r = clamp(roughness, kMinRoughness, 1.0), mu = clamp(nv, 0.0, 1.0);
  float x = clamp(r * 16.0 - 0.5, 0.0, 15.0), y = clamp(mu * 16.0 - 0.5, 0.0, 15.0);
  int x0 = min(int(x), 14), y0 = min(int(y), 14);
  float fx = x - float(x0), fy = y - float(y0);
  return mix(mix(dfgAt(x0, y0), dfgAt(x0 + 1, y0), fx), mix(dfgAt(x0, y0 + 1), dfgAt(x0 + 1, y0 + 1), fx), fy);
}
vec3 multiScatterCompensation(vec3 f0, vec2 e) {
  return 1.0 + f0 * (1.0 / max(e.x + e.y, 1e-3) - 1.0);
}
vec3 multiScatterCompensation(vec3 f0, float roughness, float nv) {
  return multiScatterCompensation(f0, dfg(roughness, nv));
}
void splitScattering(vec3 f0, float f90, vec2 e, out vec3 single, out vec3 multiple) {
  single = f0 * e.x + f90 * e.y;
  float lost = 1.0 - e.x - e.y;
  vec3 average = f0 + (1.0 - f0) * (1.0 / 21.0);
  multiple = single * average / (1.0 - lost * average) * lost;
}
vec3 scatteredShare(vec3 f0, float f90, vec2 e) {
  vec3 single, multiple;
  splitScattering(f0, f90, e, single, multiple);
  return single + multiple;
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
