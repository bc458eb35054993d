#pragma once
// Reflection maps (Halle 5.6.7): the distant environment a mirror-like
// material reflects. Every back end reconstructs the unnormalised
// reflection vector R per pixel (Halle eq. 5.2: interpolating unnormalised
// R is exact because the lookup normalises) and looks it up here, in C++
// for the CPU back end and in GLSL for the GL ones, from the same texels.
//
// Two kinds, told apart by the image's shape:
//   cube        6:1, square faces +X -X +Y -Y +Z -Z left to right, each in
//               GL's cube map convention (GL 4.5 table 8.19): s to the right,
//               t down the image. The lookup picks the face per pixel.
//   sphere pair 2:1, two mirrored-ball sphere maps (GL_SPHERE_MAP's
//               parameterisation): the left one seen from +z, used for
//               directions towards the cameras (R.z >= 0), the right one
//               seen from -z for the rest, so neither uses its poorly
//               sampled rim.
// Filtering: bilinear on the base level, clamped to each face's or map's
// edge (no seamless cube filtering, no MIP chain: see SCENE_FORMAT.md).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "mvr/gl/gl_handles.h"
#include "mvr/scene.h"

namespace mvr::shading {

enum class EnvironmentKind { Cube = 0, SpherePair = 1 };

class EnvironmentSet {
 public:
  struct Map {
    EnvironmentKind kind = EnvironmentKind::Cube;
    int layer = -1;  // -1: the material reflects nothing
  };

  // Loads every distinct map the materials name (errors name the file).
  static EnvironmentSet load(const Scene& scene);

  bool empty() const { return cubeLayers_ == 0 && sphereLayers_ == 0; }
  const std::vector<Map>& materialMaps() const { return materialMap_; }

  // Environment radiance in direction r (any length; black for zero).
  glm::vec3 sample(const Map& map, glm::vec3 r) const;

  // GL textures (need a current context; empty when the set has no map of
  // that kind): a cube map array, and a 2D array with two layers per pair.
  // Shaders read them at these units.
  static constexpr unsigned kCubeUnit = 4, kSphereUnit = 5;
  gl::Texture uploadCubes() const;
  gl::Texture uploadSpheres() const;

 private:
  glm::vec3 texel(const std::vector<uint8_t>& texels, int size, int layer, int x, int y) const;
  glm::vec3 bilinear(const std::vector<uint8_t>& texels, int size, int layer, glm::vec2 st) const;

  int cubeSize_ = 0, cubeLayers_ = 0;      // cube faces: cubeLayers_ x 6 x size^2
  int sphereSize_ = 0, sphereLayers_ = 0;  // sphere maps: sphereLayers_ x size^2
  std::vector<uint8_t> cube_, sphere_;     // sRGB-encoded RGBA8, row 0 at t = 0
  std::vector<Map> materialMap_;
};

// The reflection vector from its affine form (ShadingPlan::reflect): A, then
// M's xx yy zz xy xz yz; R = A + M eye.
glm::vec3 reflectionVector(const float* affine, const glm::vec3& eye);

// GLSL, after glslSpecular(): `vec3 reflectionVector(vec3 a, vec3 mDiag,
// vec3 mOff, vec3 eye)` and `vec3 environmentLight(int material, vec3 r)`
// (reflectivity times the environment; black for materials without a map).
const std::string& glslEnvironment();

}  // namespace mvr::shading
