#include "shading/environment_set.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "mvr/error.h"
#include "mvr/image.h"
#include "mvr/images/image_file.h"
#include "shading/bilinear.h"
#include "shading/cube_faces.h"

namespace mvr::shading {
namespace {

struct Loaded {
  EnvironmentKind kind;
  Image image;
};

EnvironmentKind kindOf(const Image& img, const std::string& path) {
  if (img.width == 6 * img.height) return EnvironmentKind::Cube;
  if (img.width == 2 * img.height) return EnvironmentKind::SpherePair;
  fail(path, "a reflection map must be a 6:1 cube strip or a 2:1 sphere map pair, not " +
                 std::to_string(img.width) + "x" + std::to_string(img.height));
}

// GL_SPHERE_MAP's coordinates for unit n; the back map sees the world
// turned half way round the y axis.
glm::vec2 sphereCoordinates(glm::vec3 n, bool back) {
  if (back) n = glm::vec3(-n.x, n.y, -n.z);
  const float m = 2.0f * std::sqrt(n.x * n.x + n.y * n.y + (n.z + 1.0f) * (n.z + 1.0f));
  return glm::vec2(n.x, n.y) / m + 0.5f;
}

// Each image is `count` squares side by side; all squares resampled to the
// largest one's size (returned in size), one after another, as sRGB-encoded
// RGBA8.
std::vector<uint8_t> packSquares(const std::vector<Image>& images, int count, bool bottomUp, int& size) {
  size = 0;
  for (const Image& img : images) size = std::max(size, img.height);
  std::vector<uint8_t> texels;
  for (const Image& img : images)
    for (int k = 0; k < count; ++k) {
      const int s = img.height;
      const std::vector<uint8_t> square = resampleSrgb8(img, {k * s, 0, s, s}, size, size, bottomUp);
      texels.insert(texels.end(), square.begin(), square.end());
    }
  return texels;
}

}  // namespace

EnvironmentSet EnvironmentSet::load(const Scene& scene) {
  EnvironmentSet set;
  std::map<std::string, Map> mapOf;
  std::vector<Image> cubes, spheres;
  for (const Material& m : scene.materials) {
    if (m.reflectionMap.empty()) {
      set.materialMap_.push_back({});
      continue;
    }
    auto it = mapOf.find(m.reflectionMap);
    if (it == mapOf.end()) {
      Image img = readImage(m.reflectionMap);
      const EnvironmentKind kind = kindOf(img, m.reflectionMap);
      std::vector<Image>& list = kind == EnvironmentKind::Cube ? cubes : spheres;
      it = mapOf.emplace(m.reflectionMap, Map{kind, int(list.size())}).first;
      list.push_back(std::move(img));
    }
    set.materialMap_.push_back(it->second);
  }
  // Every map resampled to the largest face or map of its kind.
  set.cube_ = packSquares(cubes, 6, false, set.cubeSize_);
  set.sphere_ = packSquares(spheres, 2, true, set.sphereSize_);
  set.cubeLayers_ = int(cubes.size());
  set.sphereLayers_ = int(spheres.size());
  return set;
}

glm::vec3 EnvironmentSet::texel(const std::vector<uint8_t>& texels, int size, int layer, int x,
                                int y) const {
  x = std::clamp(x, 0, size - 1), y = std::clamp(y, 0, size - 1);
  const uint8_t* p = texels.data() + ((size_t(layer) * size + y) * size + x) * 4;
  return glm::vec3(decodeSrgb8(p));
}

glm::vec3 EnvironmentSet::bilinear(const std::vector<uint8_t>& texels, int size, int layer,
                                   glm::vec2 st) const {
  return shading::bilinear(st.x * float(size) - 0.5f, st.y * float(size) - 0.5f,
                           [&](int x, int y) { return texel(texels, size, layer, x, y); });
}

glm::vec3 EnvironmentSet::sample(const Map& map, glm::vec3 r) const {
  if (map.layer < 0 || !(glm::dot(r, r) > 1e-30f) || !std::isfinite(glm::dot(r, r)))
    return glm::vec3(0.0f);
  if (map.kind == EnvironmentKind::Cube) {
    glm::vec2 st;
    const int face = cubeFace(r, st);
    return bilinear(cube_, cubeSize_, 6 * map.layer + face, st);
  }
  const glm::vec3 n = glm::normalize(r);
  const bool back = n.z < 0.0f;
  return bilinear(sphere_, sphereSize_, 2 * map.layer + int(back), sphereCoordinates(n, back));
}

namespace {

gl::Texture uploadLayers(GLenum target, int size, int depth, const std::vector<uint8_t>& texels) {
  if (depth == 0) return {};
  gl::Texture tex = gl::Texture::array2D(target, GL_SRGB8_ALPHA8, size, size, depth);  // decoded by GL
  tex.uploadLayers(0, depth, size, size, GL_RGBA, GL_UNSIGNED_BYTE, texels.data());
  gl::checkError("uploading reflection maps");
  return tex;
}

}  // namespace

gl::Texture EnvironmentSet::uploadCubes() const {
  // The CPU lookup filters each face on its own, as non-seamless GL does.
  gl::Disable(GL_TEXTURE_CUBE_MAP_SEAMLESS);
  return uploadLayers(GL_TEXTURE_CUBE_MAP_ARRAY, cubeSize_, 6 * cubeLayers_, cube_);
}

gl::Texture EnvironmentSet::uploadSpheres() const {
  return uploadLayers(GL_TEXTURE_2D_ARRAY, sphereSize_, 2 * sphereLayers_, sphere_);
}

glm::vec3 reflectionVector(const float* m, const glm::vec3& e) {
  return glm::vec3(m[0] + m[3] * e.x + m[6] * e.y + m[7] * e.z,
                   m[1] + m[6] * e.x + m[4] * e.y + m[8] * e.z,
                   m[2] + m[7] * e.x + m[8] * e.y + m[5] * e.z);
}

// Keep in step with sample() and reflectionVector() above.
const std::string& glslEnvironment() {
  static const std::string src = R"(
layout(binding = 4) uniform samplerCubeArray uCubeMaps;
layout(binding = 5) uniform sampler2DArray uSphereMaps;

vec3 reflectionVector(vec3 a, vec3 d, vec3 o, vec3 e) {
  return a + vec3(d.x * e.x + o.x * e.y + o.y * e.z,
                  o.x * e.x + d.y * e.y + o.z * e.z,
                  o.y * e.x + o.z * e.y + d.z * e.z);
}

vec3 environmentLight(int material, vec3 r) {
  Material m = uMaterials[material];
  float layer = m.params.z;
  if (layer < 0.0 || !(dot(r, r) > 1e-30)) return vec3(0.0);
  if (m.params.w == 0.0) return m.reflectivity.rgb * textureLod(uCubeMaps, vec4(r, layer), 0.0).rgb;
  vec3 n = normalize(r);
  bool back = n.z < 0.0;
  if (back) n = vec3(-n.x, n.y, -n.z);
  float k = 2.0 * sqrt(n.x * n.x + n.y * n.y + (n.z + 1.0) * (n.z + 1.0));
  vec3 st = vec3(n.xy / k + 0.5, 2.0 * layer + (back ? 1.0 : 0.0));
  return m.reflectivity.rgb * textureLod(uSphereMaps, st, 0.0).rgb;
}
)";
  return src;
}

}  // namespace mvr::shading
