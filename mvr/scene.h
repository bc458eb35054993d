#pragma once
// The scene as flat arrays (structure of arrays): what every back end reads.
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "mvr/bounds.h"
#include "mvr/camera.h"

namespace mvr {

struct Image;
struct SceneAnimation;  // mvr/scene_animation.h: what poses a scene, which it holds
namespace shading {
class ImageLight;  // shading/image_light.h: an environment's prefiltered maps
}

// Phong and Blinn-Phong: a highlight of colour `specular` and exponent
// `shininess`. Ggx: glTF's metallic-roughness lobe (shading/brdf.h), with
// `specular` its reflectance at normal incidence F0 and `roughness` its
// width; `diffuse` is then c_diff, the base colour's non-metallic part.
enum class SpecularModel { Phong, BlinnPhong, Ggx };

struct Material {
  std::string name = "default";
  glm::vec3 diffuse{0.8f};
  std::string texture;        // image file, empty for none
  // The texture's texels where they came inside the scene's file (glTF's
  // embedded images): `texture` then names them, not a file.
  std::shared_ptr<const Image> textureImage;
  glm::vec3 specular{0.0f};   // zero: no view-dependent pass needed
  float shininess = 32.0f;
  SpecularModel specularModel = SpecularModel::BlinnPhong;
  float roughness = 1.0f;     // Ggx: perceptual roughness, alpha = roughness^2
  float specularF90 = 1.0f;   // Ggx: reflectance at grazing (KHR_materials_specular)
  // Ggx: the dielectric's F0 alone (0.04 at ior 1.5): the Fresnel term that
  // takes its share of the light off the diffuse part (glTF's fresnel_mix).
  glm::vec3 dielectricF0{0.04f};
  std::string reflectionMap;  // empty for none
  glm::vec3 reflectivity{1.0f};  // scales the reflected environment
  bool twoSided = true;       // false: back faces are culled
  // Light the surface gives off itself (glTF's emissive): added after the
  // lighting and the texture, and not multiplied by either.
  glm::vec3 emission{0.0f};
  // Its texels (linear RGB) times `emission`, per texel, on the base
  // texture's coordinates (glTF's emissiveTexture); empty for none.
  std::string emissionTexture;
  std::shared_ptr<const Image> emissionImage;  // as textureImage
  // Lit by nothing (glTF's KHR_materials_unlit): the surface shows its
  // diffuse colour times its texture, whatever the lights.
  bool unlit = false;
  // Cut-out (glTF's alphaMode MASK): where the texture's alpha is below
  // this, the surface is not there at all: neither drawn nor hiding what
  // is behind it. 0: opaque. Only a textured material has a mask.
  float alphaCutoff = 0.0f;
  bool masked() const { return alphaCutoff > 0.0f && !texture.empty(); }

  // glTF's metallic-roughness as this model (Ggx): c_diff = mix(base,
  // black, metallic) as the diffuse colour, F0 = mix(dielectricF0, base,
  // metallic) and F90 = mix(dielectricF90, 1, metallic) (KHR_materials_ior
  // and _specular set the dielectric's; 0.04 and 1 without them).
  void setMetallicRoughness(const glm::vec3& base, float metallic, float roughness,
                            const glm::vec3& dielectricF0 = glm::vec3(0.04f), float dielectricF90 = 1.0f);
};

// A reflectance, vertex or light colour: every channel in [0, 1] (NaN is
// not). Scene files and mesh files are held to it.
inline bool isUnitColor(const glm::vec3& c) {
  return glm::all(glm::greaterThanEqual(c, glm::vec3(0.0f))) && glm::all(glm::lessThanEqual(c, glm::vec3(1.0f)));
}

// Lights a scene may have: the shading passes' fixed arrays.
inline constexpr int kMaxLights = 8;

struct Light {
  enum class Type { Directional, Point, Spot };
  Type type = Type::Directional;
  glm::vec3 vector{0.0f, 0.0f, -1.0f};  // direction light travels, or position
  glm::vec3 color{1.0f};
  // A spot light's cone (glTF's): full light within cosInner of its axis,
  // none outside cosOuter, a smooth square falloff between (coneFactor).
  glm::vec3 axis{0.0f, 0.0f, -1.0f};  // unit, the direction light travels
  float cosInner = 1.0f, cosOuter = 0.70710678f;
  // A point or spot light in physical units (glTF's candela): its colour
  // is what reaches distance 1, and it falls off as 1/d^2, windowed to
  // zero at `range` (0: no range) as KHR_lights_punctual recommends.
  bool falloff = false;
  float range = 0.0f;
  // What `--exposure auto` multiplies it by (shading::applyExposure): 1,
  // or for a file's lights in physical units (glTF's lux and candela),
  // what brings their illuminance at the centre of the file's bounds to a
  // sum of 1, as a camera's automatic exposure would. Per light, so that
  // a scene file's meshes keep their own files' exposures.
  float autoExposure = 1.0f;
  bool positional() const { return type != Type::Directional; }
};

// The share of a light's colour that reaches a surface point from unit
// direction l (from the point towards the light): 1 for every light but a
// spot, and for a spot t^2 with t = (cos angle - cosOuter) / (cosInner - cosOuter) in
// [0, 1], as glTF's KHR_lights_punctual recommends. As scale and offset,
// t = cos angle * scale + offset, so that GLSL needs no branch: a light
// that is no spot has (0, 1).
glm::vec2 coneScaleOffset(const Light& light);
float coneFactor(const Light& light, const glm::vec3& l);
// The share of a falloff light's colour that reaches point p: 1 / d^2
// (d at least 0.1, three.js's floor) times clamp(1 - (d / range)^4, 0, 1);
// 1 for every other light.
float distanceFalloff(const Light& light, const glm::vec3& p);
// What of a light reaches point p from unit direction l (towards the
// light): its colour times coneFactor and distanceFalloff.
glm::vec3 incidentLight(const Light& light, const glm::vec3& p, const glm::vec3& l);

// A camera a scene file holds (glTF's perspective cameras): it sits at
// toWorld's origin, looks down its -z with +y up. `--camera` makes one the
// rig's centre view (mvr/file_camera.h).
struct FileCamera {
  std::string name;
  glm::mat4 toWorld{1.0f};
  double yfov = 0.8;  // vertical field of view, radians
};

// Image-based light (`--environment`, a scene file's "environment"): a
// distant equirectangular radiance map round the scene, in three.js's
// EquirectangularReflectionMapping axes, lighting every lit material's
// diffuse and a metallic-roughness material's specular lobe.
struct Environment {
  std::string file;        // equirectangular .hdr or .exr
  float intensity = 1.0f;  // radiance scale (an exposure multiplies it)
  // Scene directions to the map's: its turns (turn()), and whatever
  // Scene::transform() has turned the scene by since its file.
  glm::mat3 fromScene{1.0f};
  // The maps, once loaded (shading::loadEnvironment); shared by the
  // scene's copies (a sequence's frames).
  std::shared_ptr<const shading::ImageLight> light;
  // Turns the map by `degrees` about +y, as three.js's
  // environmentRotation.y: a direction looks it up turned back.
  void turn(float degrees);
};

struct Scene {
  // Per vertex.
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;
  std::vector<glm::vec3> colors;  // vertex colours, multiplied by the material's
  std::vector<glm::vec2> uvs;     // empty when no mesh has texture coordinates
  // Per triangle.
  std::vector<glm::uvec3> triangles;
  std::vector<uint32_t> materialIds;

  std::vector<Material> materials;
  std::vector<Light> lights;
  glm::vec3 ambient{0.15f};
  // The lights and the ambient are loading's defaults, not a file's: an
  // environment takes their place.
  bool defaultLights = false, defaultAmbient = true;
  std::optional<Environment> environment;
  // Shaded for a tone map (`--tonemap`): the lit diffuse colour is not
  // clamped to 1 before the texture and highlights (it is without one, so
  // that today's images keep their bytes).
  bool highDynamicRange = false;
  // The colours are data (depth, mvr/depth.h), not reflectances: back ends
  // keep them in float wherever they store them (the G-buffer's albedo).
  bool exactColors = false;
  std::optional<CameraSpec> camera;  // from the scene file, if it had one
  std::vector<FileCamera> fileCameras;  // the files' own cameras, in world coordinates
  // The files' animations (mvr/scene_animation.h): what poses the scene at
  // a time of a sequence. Empty for a still scene.
  std::vector<std::shared_ptr<const SceneAnimation>> animations;
  std::string source;                // file it came from, for manifests
  // What transform() has moved the scene by since its file (a mesh file
  // centred on its bounds, a file camera's view, the focal plane): the
  // file's coordinates to these. The manifest gives it.
  glm::mat4 fromFile{1.0f};
  // Faces of the files that could not be used (a repeated corner or one
  // naming a vertex that does not exist): dropped, and counted here.
  size_t droppedFaces = 0;
  // What loading took other than as written, a line each ("FILE:3: ..."):
  // the commands print them as warnings.
  std::vector<std::string> warnings;

  size_t vertexCount() const { return positions.size(); }
  size_t triangleCount() const { return triangles.size(); }
  Bounds bounds() const;
  // Per vertex: its material. A vertex belongs to one mesh, so any of its
  // triangles names it.
  std::vector<uint32_t> vertexMaterials() const;
  // Appends another scene's geometry, materials and file cameras (lights
  // stay ours).
  void append(const Scene& other);
  // Moves everything placed in the world by m: positions, normals, lights
  // and file cameras (in double: a scale of 1e-20 inverted is 1e20, and a
  // normal times that squared overflows float).
  void transform(const glm::mat4& m);
  // The positions and normals alone (a model turning under fixed lights).
  void transformGeometry(const glm::mat4& m);
};

}  // namespace mvr

namespace mvr {
// Area-weighted vertex normals from the triangles (meshes without normals).
void computeVertexNormals(Scene& scene);
}  // namespace mvr
