#pragma once
// Pass planning (Halle 5.6.9): a scene pays only for the shading its
// materials use. The diffuse pass always runs; a texture pass when some
// material has a texture; one view-dependent pass when some material is
// specular or reflective. Passes accumulate in a float target: texture
// multiplies, the view-dependent pass adds.
//
// The plan also fixes the per-vertex attributes beyond the lit colours that
// the extreme-vertex transform must carry (all divided by w): the "extras".
#include <string>
#include <vector>

#include "mvr/scene.h"

namespace mvr::shading {

enum class Pass { Diffuse, Texture, ViewDependent };

struct ShadingPlan {
  bool texture = false;     // some material has a texture
  bool specular = false;    // some material has a non-zero specular colour
  bool reflection = false;  // some material has a reflection map
  // Some material gives off light. It rides in the lit colours; where a
  // texture pass runs, that pass gives back what its multiply took of it.
  bool emission = false;
  // Some material's emission has a texture (Material::emissionTexture):
  // every back end samples it per pixel (EMISSION_TEXTURE), and its
  // material counts as textured.
  bool emissionTexture = false;
  // Some material is a cut-out (Material::masked): the pass that writes
  // depth must sample its texture's alpha. MVR's GL passes add a depth
  // pass for it.
  bool mask = false;
  // Some light is a spot: the GLSL lighting takes cones (SPOT_LIGHTS);
  // without one it skips them (8% of svr's time on llvmpipe).
  bool spots = false;
  // Some light falls off with distance (Light::falloff): FALLOFF_LIGHTS.
  bool falloff = false;
  // Some lit material is glTF's metallic-roughness (SpecularModel::Ggx):
  // the view-dependent pass takes off the diffuse light its Fresnel term
  // reflects instead (GGX; shading::diffuseFresnelLoss), which needs the
  // diffuse albedo per pixel.
  bool ggx = false;
  // The scene has an image-based light (Scene::environment): its
  // irradiance joins every lit diffuse colour, and a Ggx material's
  // view-dependent pass adds its prefiltered radiance (ENVIRONMENT).
  bool environment = false;

  // Offsets into the per-vertex extras; -1 when absent.
  int uv = -1;        // 2 floats: texture coordinates
  int position = -1;  // 3 floats: world position (view-dependent pass)
  int normal = -1;    // 3 floats: world normal, front side
  int albedo = -1;    // 3 floats: diffuse albedo (ggx), right after the normal
  // 9 floats: the reflection vector as an affine function of the eye E,
  // R(E) = A + M E with A = P - 2 (N.P) N and M = 2 N N^T - I (xx yy zz xy
  // xz yz): unnormalised R is linear in E, so interpolating A and M is
  // interpolating R (Halle eq. 5.2) for every view and row at once, and
  // both are the same for either side of the surface.
  int reflect = -1;
  int extraCount = 0;

  std::vector<Pass> passes() const;
  std::string passNames() const;  // e.g. "diffuse+texture"
  // "#define TEXTURE", "#define VIEW_DEPENDENT" and "#define REFLECT"
  // lines for the passes after the first, "#define EMISSION",
  // "#define EMISSION_TEXTURE" and "#define MASK", and SPOT_LIGHTS,
  // FALLOFF_LIGHTS, GGX and ENVIRONMENT as above: shaders that compute
  // every pass at once.
  std::string glslDefines() const;
};

constexpr int kMaxExtras = 20;

ShadingPlan planShading(const Scene& scene);
// Per vertex, plan.extraCount floats laid out as the plan says.
std::vector<float> vertexExtras(const Scene& scene, const ShadingPlan& plan);
const char* passName(Pass pass);

}  // namespace mvr::shading
