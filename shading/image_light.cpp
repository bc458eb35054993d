#include "shading/image_light.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <mutex>

#include "mvr/error.h"
#include "mvr/gl/gl_program.h"
#include "mvr/image.h"
#include "mvr/images/image_file.h"
#include "mvr/parallel.h"
#include "shading/bilinear.h"
#include "shading/brdf.h"
#include "shading/cube_faces.h"

namespace mvr::shading {
namespace {

constexpr float kPi = float(M_PI);

// The source as linear RGB, read with bilinear filtering, wrapped in u and
// clamped at the poles. Channels outside [0, kMaxRadiance] (NaN, infinite,
// negative, or beyond half float's range, which the GL copy has) are
// brought into it and counted: one bad texel would otherwise spread
// through the harmonics and every prefiltered level.
class Equirect {
 public:
  explicit Equirect(const Image& img) : w_(img.width), h_(img.height), px_(size_t(w_) * h_) {
    for (int y = 0; y < h_; ++y)
      for (int x = 0; x < w_; ++x) {
        glm::vec3 c(img.linear(x, y));
        bool bad = false;
        for (int k = 0; k < 3; ++k) {
          const float v = std::isnan(c[k]) || c[k] < 0.0f ? 0.0f : std::min(c[k], ImageLight::kMaxRadiance);
          bad |= v != c[k];
          c[k] = v;
        }
        changed_ += bad;
        px_[size_t(y) * w_ + x] = c;
      }
  }
  size_t changed() const { return changed_; }

  glm::vec3 sample(const glm::vec3& dir) const {
    const glm::vec3 d = glm::normalize(dir);
    const float u = std::atan2(d.z, d.x) / (2.0f * kPi) + 0.5f;
    const float v = std::asin(std::clamp(d.y, -1.0f, 1.0f)) / kPi + 0.5f;
    return bilinear(u * float(w_) - 0.5f, (1.0f - v) * float(h_) - 0.5f, [&](int x, int y) {
      x = ((x % w_) + w_) % w_, y = std::clamp(y, 0, h_ - 1);
      return px_[size_t(y) * w_ + x];
    });
  }

 private:
  int w_, h_;
  std::vector<glm::vec3> px_;
  size_t changed_ = 0;
};

// The unpadded base faces and their box-filtered halvings down to 1 x 1:
// what prefiltering reads at the level a sample's solid angle asks for.
class CubePyramid {
 public:
  explicit CubePyramid(std::vector<glm::vec3> base, int size) {
    levels_.push_back(std::move(base));
    sizes_.push_back(size);
    while (size > 1) {
      const int half = size / 2;
      const std::vector<glm::vec3>& fine = levels_.back();
      std::vector<glm::vec3> coarse(size_t(6) * half * half);
      for (int f = 0; f < 6; ++f)
        for (int y = 0; y < half; ++y)
          for (int x = 0; x < half; ++x) {
            auto at = [&](int i, int j) { return fine[(size_t(f) * size + j) * size + i]; };
            coarse[(size_t(f) * half + y) * half + x] =
                0.25f * (at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1));
          }
      levels_.push_back(std::move(coarse));
      sizes_.push_back(size = half);
    }
  }

  glm::vec3 sample(const glm::vec3& dir, float lod) const {
    glm::vec2 st;
    const int face = cubeFace(dir, st);
    const float l = std::clamp(lod, 0.0f, float(levels_.size() - 1));
    const int k = std::min(int(l), int(levels_.size()) - 2);
    if (k < 0) return faceTexels(0, face, st);
    return glm::mix(faceTexels(k, face, st), faceTexels(k + 1, face, st), l - float(k));
  }

 private:
  glm::vec3 faceTexels(int level, int face, const glm::vec2& st) const {
    const int n = sizes_[size_t(level)];
    const std::vector<glm::vec3>& t = levels_[size_t(level)];
    return bilinear(st.x * float(n) - 0.5f, st.y * float(n) - 0.5f, [&](int x, int y) {
      x = std::clamp(x, 0, n - 1), y = std::clamp(y, 0, n - 1);
      return t[(size_t(face) * n + y) * n + x];
    });
  }

  std::vector<std::vector<glm::vec3>> levels_;
  std::vector<int> sizes_;
};

// Texel (x, y) of a padded face of size s: its direction, the border's
// continuing the face's plane.
glm::vec3 paddedDirection(int face, int s, float x, float y) {
  return glm::normalize(cubeDirection(face, 2.0f * (x - 0.5f) / float(s) - 1.0f, 2.0f * (y - 0.5f) / float(s) - 1.0f));
}

// Every padded texel of every face, on the pool.
std::vector<glm::vec3> fillLevel(int s, const std::function<glm::vec3(int face, int x, int y)>& texel) {
  const int p = s + 2;
  std::vector<glm::vec3> out(size_t(6) * p * p);
  parallelFor(0, 6 * p, [&](int row) {
    const int face = row / p, y = row % p;
    for (int x = 0; x < p; ++x) out[(size_t(face) * p + y) * p + x] = texel(face, x, y);
  });
  return out;
}

// One GGX importance sample for a texel whose lobe is about +z (n = v =
// r): the light direction, its cosine weight, and the source level its
// solid angle covers (filtered importance sampling, Krivanek and Colbert
// 2008, one level up to smooth the remaining noise).
struct LobeSample {
  glm::vec3 l;
  float weight, lod;
};

std::vector<LobeSample> lobeSamples(float roughness, int count) {
  const float alpha = roughness * roughness;
  const float texelSolidAngle = 4.0f * kPi / (6.0f * float(ImageLight::kBaseSize) * float(ImageLight::kBaseSize));
  std::vector<LobeSample> samples;
  for (int i = 0; i < count; ++i) {
    const glm::vec3 h = ggxHalfVector(hammersley(uint32_t(i), uint32_t(count)), alpha);
    const glm::vec3 l = 2.0f * h.z * h - glm::vec3(0.0f, 0.0f, 1.0f);
    if (l.z <= 0.0f) continue;
    const float pdf = ggxDistribution(alpha, h.z) / 4.0f;  // of l: D (n.h) / (4 v.h), with v = n
    const float solidAngle = 1.0f / (float(count) * pdf);
    samples.push_back({l, l.z, std::max(0.5f * std::log2(solidAngle / texelSolidAngle) + 1.0f, 0.0f)});
  }
  return samples;
}

glm::vec3 prefiltered(const CubePyramid& source, const std::vector<LobeSample>& samples, const glm::vec3& n) {
  const glm::vec3 up = std::abs(n.z) < 0.999f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 t = glm::normalize(glm::cross(up, n)), b = glm::cross(n, t);
  glm::vec3 sum(0.0f);
  float weight = 0.0f;
  for (const LobeSample& s : samples) {
    sum += s.weight * source.sample(t * s.l.x + b * s.l.y + n * s.l.z, s.lod);
    weight += s.weight;
  }
  return sum / weight;
}

// 1, y, z, x, xy, yz, 3z^2 - 1, xz, x^2 - y^2 and the real spherical
// harmonics' constants that make them Y_lm; the cosine lobe's A_l / pi.
std::array<float, 9> shBasis(const glm::vec3& n) {
  return {1.0f, n.y, n.z, n.x, n.x * n.y, n.y * n.z, 3.0f * n.z * n.z - 1.0f, n.x * n.z, n.x * n.x - n.y * n.y};
}
constexpr std::array<float, 9> kShConstant = {0.282095f, 0.488603f, 0.488603f, 0.488603f, 1.092548f,
                                              1.092548f, 0.315392f, 1.092548f, 0.546274f};
constexpr std::array<float, 9> kCosineLobe = {1.0f, 2.0f / 3.0f, 2.0f / 3.0f, 2.0f / 3.0f, 0.25f,
                                              0.25f, 0.25f, 0.25f, 0.25f};

}  // namespace

int ImageLight::levelSize(int level) { return std::max(kBaseSize >> level, kMinSize); }

float ImageLight::levelRoughness(int level) {
  return level == 0 ? 0.0f : 0.125f * std::pow(std::sqrt(2.0f), float(level - 1));
}

// Keep in step with the GLSL below.
float ImageLight::levelOf(float roughness) {
  const float r = std::clamp(roughness, 0.0f, 1.0f);
  return r <= 0.125f ? r / 0.125f : std::min(1.0f + 2.0f * std::log2(r / 0.125f), float(kLevels - 1));
}

ImageLight::ImageLight(const Image& equirect, int samples) {
  if (equirect.width < 2 || equirect.height < 1) fail("environment", "the map is empty");
  const Equirect source(equirect);
  changedTexels_ = source.changed();
  // The mirror level: 2 x 2 samples of the map a texel.
  const int s0 = levelSize(0);
  levels_.push_back(fillLevel(s0, [&](int face, int x, int y) {
    glm::vec3 sum(0.0f);
    for (float oy : {-0.25f, 0.25f})
      for (float ox : {-0.25f, 0.25f}) sum += source.sample(paddedDirection(face, s0, float(x) + ox, float(y) + oy));
    return 0.25f * sum;
  }));
  std::vector<glm::vec3> base(size_t(6) * s0 * s0);
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < s0; ++y)
      for (int x = 0; x < s0; ++x) base[(size_t(f) * s0 + y) * s0 + x] = texel(0, f, x + 1, y + 1);
  // The harmonics from the base faces, each texel weighted by its solid angle.
  std::array<glm::dvec3, 9> sum{};
  for (int f = 0; f < 6; ++f)
    for (int y = 0; y < s0; ++y)
      for (int x = 0; x < s0; ++x) {
        const float sc = (2.0f * float(x) + 1.0f) / float(s0) - 1.0f, tc = (2.0f * float(y) + 1.0f) / float(s0) - 1.0f;
        const float solidAngle = 4.0f / (float(s0) * float(s0)) / std::pow(1.0f + sc * sc + tc * tc, 1.5f);
        const std::array<float, 9> b = shBasis(glm::normalize(cubeDirection(f, sc, tc)));
        const glm::dvec3 l = glm::dvec3(base[(size_t(f) * s0 + y) * s0 + x]) * double(solidAngle);
        for (int i = 0; i < 9; ++i) sum[size_t(i)] += l * double(b[size_t(i)] * kShConstant[size_t(i)]);
      }
  for (int i = 0; i < 9; ++i)
    sh_[size_t(i)] = glm::vec3(sum[size_t(i)] * double(kCosineLobe[size_t(i)] * kShConstant[size_t(i)]));
  const CubePyramid pyramid(std::move(base), s0);
  for (int k = 1; k < kLevels; ++k) {
    const int s = levelSize(k);
    const std::vector<LobeSample> lobe = lobeSamples(levelRoughness(k), std::min(samples << (k - 1), kMaxSamples));
    levels_.push_back(fillLevel(s, [&](int face, int x, int y) {
      return prefiltered(pyramid, lobe, paddedDirection(face, s, float(x), float(y)));
    }));
  }
}

std::shared_ptr<const ImageLight> ImageLight::load(const std::string& path) {
  const Image img = readImage(path);
  if (img.width != 2 * img.height)
    fail(path, "an environment must be an equirectangular (2:1) map, not " + std::to_string(img.width) + "x" +
                   std::to_string(img.height));
  return std::make_shared<const ImageLight>(img);
}

glm::vec3 ImageLight::texel(int level, int face, int x, int y) const {
  const int p = levelSize(level) + 2;
  x = std::clamp(x, 0, p - 1), y = std::clamp(y, 0, p - 1);
  return levels_[size_t(level)][(size_t(face) * p + y) * p + x];
}

// Keep in step with the GLSL below.
glm::vec3 ImageLight::faceRadiance(int level, int face, const glm::vec2& st) const {
  const int s = levelSize(level), p = s + 2;
  const glm::vec3* t = levels_[size_t(level)].data() + size_t(face) * p * p;
  // Padded texels, centres at +0.5; st in [0, 1] keeps the four within the
  // padded face (the clamp only catches rounding).
  return bilinear(st.x * float(s) + 0.5f, st.y * float(s) + 0.5f, [&](int x, int y) {
    return t[std::clamp(y, 0, p - 1) * p + std::clamp(x, 0, p - 1)];
  });
}

glm::vec3 ImageLight::levelRadiance(const glm::vec3& r, int level) const {
  glm::vec2 st;
  const int face = cubeFace(r, st);
  return faceRadiance(level, face, st);
}

glm::vec3 ImageLight::radiance(const glm::vec3& r, float roughness) const {
  const float lod = levelOf(roughness);
  const int k = std::min(int(lod), kLevels - 2);
  glm::vec2 st;
  const int face = cubeFace(r, st);
  return glm::mix(faceRadiance(k, face, st), faceRadiance(k + 1, face, st), lod - float(k));
}

glm::vec3 ImageLight::irradiance(const glm::vec3& n) const {
  const std::array<glm::vec3, 9>& c = sh_;
  const glm::vec3 e = c[0] + c[1] * n.y + c[2] * n.z + c[3] * n.x + c[4] * (n.x * n.y) + c[5] * (n.y * n.z) +
                      c[6] * (3.0f * n.z * n.z - 1.0f) + c[7] * (n.x * n.z) + c[8] * (n.x * n.x - n.y * n.y);
  return glm::max(e, glm::vec3(0.0f));
}

gl::Texture ImageLight::upload() const {
  gl::Texture tex = gl::Texture::array2D(GL_TEXTURE_2D_ARRAY, GL_RGBA16F, kPadded, kPadded, 6 * kLevels);
  for (int k = 0; k < kLevels; ++k) {
    const int p = levelSize(k) + 2;  // the level's six faces, each in its layer's corner
    tex.uploadLayers(6 * k, 6, p, p, GL_RGB, GL_FLOAT, levels_[size_t(k)].data());
  }
  gl::checkError("uploading the environment");
  return tex;
}

void loadEnvironment(Scene& scene) {
  if (!scene.environment || scene.environment->light) return;
  static std::mutex mutex;
  static std::map<std::string, std::weak_ptr<const ImageLight>> loaded;
  const std::lock_guard lock(mutex);
  std::shared_ptr<const ImageLight> light = loaded[scene.environment->file].lock();
  if (!light) loaded[scene.environment->file] = light = ImageLight::load(scene.environment->file);
  if (light->changedTexels())
    scene.warnings.push_back(scene.environment->file + ": " + std::to_string(light->changedTexels()) +
                             " texels are not numbers, negative or above 65504: read as 0 or 65504");
  scene.environment->light = std::move(light);
}

// Keep in step with the GLSL below.
glm::vec3 environmentDiffuse(const Scene& scene, const glm::vec3& n) {
  const float len = glm::length(n);
  if (!scene.environment || !scene.environment->light || !(len > 1e-20f)) return glm::vec3(0.0f);
  return scene.environment->intensity *
         scene.environment->light->irradiance(scene.environment->fromScene * (n / len));
}

glm::vec3 environmentSpecular(const Scene& scene, const Material& m, const glm::vec3& n, const glm::vec3& v,
                              const glm::vec3& irradiance, const Scattering& s) {
  if (!scene.environment || !scene.environment->light || m.specularModel != SpecularModel::Ggx)
    return glm::vec3(0.0f);
  const float roughness = std::clamp(m.roughness, kMinRoughness, 1.0f), a2 = roughness * roughness * roughness * roughness;
  // Towards the normal as the lobe widens (three.js's getIBLRadiance): a
  // rough lobe's light comes from nearer the normal than the mirror's.
  const glm::vec3 r = glm::normalize(glm::mix(glm::reflect(-v, n), n, a2));
  const glm::mat3& toMap = scene.environment->fromScene;
  const ImageLight& light = *scene.environment->light;
  return scene.environment->intensity * light.radiance(toMap * r, roughness) * s.single + irradiance * s.multiple;
}

const char* glslEnvironmentDiffuse() {
  return R"(
#ifdef ENVIRONMENT
uniform mat3 uEnvironmentFromScene;
uniform float uEnvironmentIntensity;
uniform vec3 uEnvironmentSh[9];
vec3 environmentDiffuse(vec3 nIn) {
  float len = length(nIn);
  if (!(len > 1e-20)) return vec3(0.0);
  vec3 n = uEnvironmentFromScene * (nIn / len);
  vec3 e = uEnvironmentSh[0] + uEnvironmentSh[1] * n.y + uEnvironmentSh[2] * n.z + uEnvironmentSh[3] * n.x +
           uEnvironmentSh[4] * (n.x * n.y) + uEnvironmentSh[5] * (n.y * n.z) +
           uEnvironmentSh[6] * (3.0 * n.z * n.z - 1.0) + uEnvironmentSh[7] * (n.x * n.z) +
           uEnvironmentSh[8] * (n.x * n.x - n.y * n.y);
  return uEnvironmentIntensity * max(e, vec3(0.0));
}
#endif
)";
}

const char* glslEnvironmentRadiance() {
  return R"(
#ifdef ENVIRONMENT
layout(binding = 6) uniform sampler2DArray uEnvironmentMap;
int environmentFace(vec3 r, out vec2 st) {
  vec3 a = abs(r);
  int face;
  float sc, tc, ma;
  if (a.x >= a.y && a.x >= a.z) {
    face = r.x >= 0.0 ? 0 : 1; ma = a.x; sc = r.x >= 0.0 ? -r.z : r.z; tc = -r.y;
  } else if (a.y >= a.z) {
    face = r.y >= 0.0 ? 2 : 3; ma = a.y; sc = r.x; tc = r.y >= 0.0 ? r.z : -r.z;
  } else {
    face = r.z >= 0.0 ? 4 : 5; ma = a.z; sc = r.z >= 0.0 ? r.x : -r.x; tc = -r.y;
  }
  st = 0.5 * (vec2(sc, tc) / ma + 1.0);
  return face;
}
vec3 environmentLevel(int face, vec2 st, int level) {
  float s = float(max(256 >> level, 8));
  return textureLod(uEnvironmentMap, vec3((st * s + 1.0) / 258.0, float(6 * level + face)), 0.0).rgb;
}
// r and n unit, in the scene's frame; roughness at least kMinRoughness.
vec3 environmentRadiance(vec3 r, float roughness) {
  vec2 st;
  int face = environmentFace(uEnvironmentFromScene * r, st);
  float lod = roughness <= 0.125 ? roughness / 0.125 : min(1.0 + 2.0 * log2(roughness / 0.125), 7.0);
  int k = min(int(lod), 6);
  return uEnvironmentIntensity * mix(environmentLevel(face, st, k), environmentLevel(face, st, k + 1), lod - float(k));
}
#endif
)";
}

void setEnvironmentUniforms(const gl::Program& program, const Scene& scene) {
  if (!scene.environment || !scene.environment->light) return;
  gl::setUniform(program, "uEnvironmentFromScene", scene.environment->fromScene);
  gl::setUniform(program, "uEnvironmentIntensity", scene.environment->intensity);
  const std::array<glm::vec3, 9>& sh = scene.environment->light->harmonics();
  for (int i = 0; i < 9; ++i)
    gl::setUniform(program, ("uEnvironmentSh[" + std::to_string(i) + "]").c_str(), sh[size_t(i)]);
}

}  // namespace mvr::shading
