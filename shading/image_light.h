#pragma once
// Image-based light (`--environment`): a distant equirectangular radiance
// map, split as real-time PBR splits it (Karis 2013):
//   diffuse   its irradiance over pi, E(n) / pi, from nine spherical
//             harmonics (Ramamoorthi and Hanrahan 2001): what a white
//             Lambert surface facing n sends back. View-independent, it
//             joins the ambient in every back end's diffuse pass.
//   specular  the radiance round the mirror direction, prefiltered with
//             GGX's lobe at a roughness per level (n = v = r, filtered
//             importance sampling), times the split-sum table
//             (shading/brdf.h): the view-dependent pass's.
//
// The map's directions are three.js's EquirectangularReflectionMapping:
// u = atan2(z, x) / 2pi + 1/2 across the image, v = asin(y) / pi + 1/2 up
// it (+y at the top row).
//
// Storage: per level, six cube faces of levelSize(k)^2 texels with a
// one-texel border that continues the face onto its neighbours (each
// border texel prefiltered at its own direction), so that bilinear
// filtering is seamless without GL's cube maps; GL reads the same texels
// from a 2D array, kPadded^2 a layer, level k's face f at layer 6k + f, in
// its top-left (levelSize(k) + 2)^2 corner.
#include <array>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "mvr/gl/gl_handles.h"
#include "mvr/scene.h"
#include "shading/brdf.h"

namespace mvr {
struct Image;
}

namespace mvr::shading {

class ImageLight {
 public:
  static constexpr int kBaseSize = 256, kMinSize = 8, kLevels = 8, kPadded = kBaseSize + 2;
  // Prefiltering's GGX samples a texel at level 1, doubled each level up to
  // kMaxSamples: a wider lobe needs more, on fewer texels (the cost stays
  // about even; fewer leave the rough levels 5% off their integral).
  static constexpr int kSamples = 64, kMaxSamples = 2048;
  // Half float's largest value, which the GL copy stores: texels above it
  // are clamped to it (and NaN and negative ones read as 0) on the CPU too.
  static constexpr float kMaxRadiance = 65504.0f;

  // From linear RGB, any size of at least 2 x 1 (the map is read with
  // bilinear filtering, wrapped round in u).
  explicit ImageLight(const Image& equirect, int samples = kSamples);
  // Reads an .hdr or .exr (OpenImageIO); errors name the file.
  static std::shared_ptr<const ImageLight> load(const std::string& path);

  // Level k: the mirror at 0, then roughness 0.125 sqrt(2)^(k-1) up to 1
  // at k = 7 (the lobe's width alpha = roughness^2 doubles a level, as
  // the texel's does); levelOf is its inverse, with fractions between.
  static int levelSize(int level);
  static float levelRoughness(int level);
  static float levelOf(float roughness);

  // The map's radiance round unit direction r (map frame), prefiltered
  // for roughness (interpolated between its two levels), or at one level.
  glm::vec3 radiance(const glm::vec3& r, float roughness) const;
  glm::vec3 levelRadiance(const glm::vec3& r, int level) const;
  // E(n) / pi for unit n (map frame), at least 0.
  glm::vec3 irradiance(const glm::vec3& n) const;
  // The nine coefficients irradiance() weighs 1, y, z, x, xy, yz,
  // 3z^2 - 1, xz, x^2 - y^2 by.
  const std::array<glm::vec3, 9>& harmonics() const { return sh_; }
  // How many of the map's texels were brought into [0, kMaxRadiance].
  size_t changedTexels() const { return changedTexels_; }

  // Needs a current context: the 2D array, RGBA16F, bilinear.
  gl::Texture upload() const;

 private:
  glm::vec3 texel(int level, int face, int x, int y) const;
  glm::vec3 faceRadiance(int level, int face, const glm::vec2& st) const;

  std::vector<std::vector<glm::vec3>> levels_;  // per level: 6 padded faces, row after row
  std::array<glm::vec3, 9> sh_{};
  size_t changedTexels_ = 0;
};

// Loads the scene's environment's maps if it has one and they are not
// loaded (one load per file in a process: a sequence's scenes share it).
void loadEnvironment(Scene& scene);

// For the scene's unit normal n: E(n) / pi times the intensity, 0 for a
// scene without an environment.
glm::vec3 environmentDiffuse(const Scene& scene, const glm::vec3& n);
// A Ggx material's specular from the environment for unit n and v (three.js's
// RE_IndirectSpecular): the prefiltered radiance round reflect(-v, n)
// times the lobe's single scattering, plus its multiple scattering of the
// irradiance (environmentDiffuse(scene, n)); the caller has both, the
// scattering as splitScattering(F0, F90, dfg(roughness, n.v)). 0 for other
// models and without an environment.
glm::vec3 environmentSpecular(const Scene& scene, const Material& material, const glm::vec3& n,
                              const glm::vec3& v, const glm::vec3& irradiance, const Scattering& scattering);

// GLSL under ENVIRONMENT (ShadingPlan::glslDefines), for glslLighting():
// uniforms and `vec3 environmentDiffuse(vec3 n)`.
const char* glslEnvironmentDiffuse();
// GLSL under ENVIRONMENT, for glslSpecular(): the map at
// kEnvironmentUnit and `vec3 environmentRadiance(vec3 r, float roughness)`.
const char* glslEnvironmentRadiance();
inline constexpr unsigned kEnvironmentUnit = 6;
// The uniforms glslEnvironmentDiffuse() declares (nothing without an
// environment).
void setEnvironmentUniforms(const gl::Program& program, const Scene& scene);

}  // namespace mvr::shading
