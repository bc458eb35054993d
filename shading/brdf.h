#pragma once
// glTF 2.0's metallic-roughness BRDF (specification, Appendix B), the
// specular lobe of SpecularModel::Ggx: the GGX (Trowbridge-Reitz)
// distribution D with alpha = roughness^2, the height-correlated Smith
// visibility V = G / (4 |n.l| |n.v|) and Schlick's Fresnel F between F0
// and F90. Its diffuse half, Lambert's c_diff / pi, is shading/lighting's.
//
// Units: a light's colour is its illuminance over pi (a colour-1 light
// lights a white Lambert surface facing it to 1), so the radiance a light
// sends off the lobe is pi * colour * (n.l) * F V D. That is three.js's
// irradiance * BRDF_GGX for a light of intensity pi * colour.
//
// One formula, written in C++ and GLSL side by side.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace mvr::shading {

// Roughness below this is raised to it (three.js's and Filament's floor):
// the lobe's peak D = 1 / (pi alpha^2) stays finite in float, and a
// highlight keeps at least a pixel or so at the sizes a view has.
inline constexpr float kMinRoughness = 0.045f;

float ggxDistribution(float alpha, float nh);
// The same with sin2 = 1 - nh^2 given as |n x h|^2, exact near the mirror.
float ggxDistribution(float alpha, float nh, float sin2);
float smithVisibility(float alpha, float nl, float nv);
glm::vec3 schlickFresnel(const glm::vec3& f0, float f90, float vh);

// pi F V D (n.l) for unit n, l, v: the radiance a colour-1 light sends
// towards v. Zero where l or v is below the surface.
glm::vec3 ggxLobe(const glm::vec3& f0, float f90, float roughness, const glm::vec3& n,
                  const glm::vec3& l, const glm::vec3& v);

// Point i of n of the Hammersley set in [0, 1)^2 (the radical inverse in
// base 2 as its second coordinate), and the half vector about +z that
// GGX's D (n.h) at width alpha maps it to: the importance samples of the
// BRDF table and of the environment's prefiltering.
glm::vec2 hammersley(uint32_t i, uint32_t n);
glm::vec3 ggxHalfVector(const glm::vec2& xi, float alpha);

// The split-sum BRDF table (Karis 2013), the lobe's directional albedo
// E(v) = F0 A + F90 B over the hemisphere at roughness r and n.v: A and B,
// integrated once (1024 GGX-importance samples a cell), kDfgSize^2 cells
// whose centres are at ((i + 0.5) / kDfgSize, (j + 0.5) / kDfgSize) in
// (r, n.v), read bilinearly and clamped to the edge, as a GL texture is.
inline constexpr int kDfgSize = 16;
const std::vector<glm::vec2>& dfgTable();  // row j (n.v) after row j - 1
// Read at the roughness the lobe uses (raised to kMinRoughness) and n.v
// clamped to [0, 1].
glm::vec2 dfg(float roughness, float nv);

// What the lobe loses to its single scattering, given back (Turquin 2019,
// three.js's direct light): 1 + F0 (1 / E_white - 1), E_white = A + B.
glm::vec3 multiScatterCompensation(const glm::vec3& f0, float roughness, float nv);
// The same from the table's value e = dfg(roughness, nv), for a caller that
// needs it more than once a pixel (splitScattering's too).
glm::vec3 multiScatterCompensation(const glm::vec3& f0, const glm::vec2& e);

// The Blinn-Phong exponent whose lobe is about as wide as GGX's at this
// roughness (Walter et al. 2007: 2 / alpha^2 - 2): where the highlight
// splitter places its knots.
float ggxBlinnExponent(float roughness);

// The share of a uniform surround's light the lobe reflects towards v,
// single and multiple scattering (Fdez-Aguera 2019; three.js's
// computeMultiscattering), from the table's value e = dfg(roughness, n.v):
// what a diffuse layer under it does not get.
glm::vec3 scatteredShare(const glm::vec3& f0, float f90, const glm::vec2& e);
// The same in its two parts: single scattering F0 A + F90 B, which weighs
// the prefiltered radiance, and the multiple scattering that weighs the
// irradiance (shading/image_light.h).
struct Scattering {
  glm::vec3 single, multiple;
};
Scattering splitScattering(const glm::vec3& f0, float f90, const glm::vec2& e);

// GLSL: `vec3 ggxLobe(vec3 f0, float f90, float roughness, vec3 n, vec3 l, vec3 v)`,
// and `vec2 dfg(float roughness, float nv)` over uDfg, the table that the
// Materials block (glslMaterials) opens with; multiScatterCompensation (of
// roughness and n.v, or of dfg's e), and splitScattering and
// scatteredShare of dfg's e.
const char* glslBrdf();

}  // namespace mvr::shading
