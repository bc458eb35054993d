// glTF materials as ours: metallic-roughness (with KHR_materials_ior and
// _specular), base colour and emission textures with their transforms and
// texture coordinate sets, alpha masks and KHR_materials_unlit.
#include <algorithm>
#include <cmath>
#include <utility>

#include "mvr/color.h"
#include "mvr/error.h"
#include "mvr/image.h"
#include "mvr/assets/gltf_reader.h"
#include "mvr/assets/load_warnings.h"

namespace mvr::gltf {
namespace {

glm::vec3 factor3(const std::vector<double>& f, glm::vec3 fallback) {
  if (f.size() < 3 || !std::isfinite(f[0]) || !std::isfinite(f[1]) || !std::isfinite(f[2])) return fallback;
  return glm::vec3(float(f[0]), float(f[1]), float(f[2]));
}

float finiteOr(double v, float fallback) { return std::isfinite(v) ? float(v) : fallback; }

const tinygltf::Value* extensionOf(const tinygltf::Material& g, const char* name) {
  const auto it = g.extensions.find(name);
  return it != g.extensions.end() && it->second.IsObject() ? &it->second : nullptr;
}

// The dielectric's reflectance at normal and grazing incidence:
// KHR_materials_ior's F0 = ((ior - 1) / (ior + 1))^2 (0.04 at glTF's 1.5),
// times KHR_materials_specular's colour (at most 1) and its factor, which
// also scales F90. Their textures are not drawn (said once).
std::pair<glm::vec3, float> dielectricOf(const tinygltf::Material& g, LoadWarnings& warn) {
  float f0 = 0.04f;
  if (const tinygltf::Value* x = extensionOf(g, "KHR_materials_ior")) {
    const double ior = numberOr(*x, "ior", -1, 1.5);
    if (ior >= 1.0) f0 = float(std::pow((ior - 1.0) / (ior + 1.0), 2.0));
  }
  glm::vec3 colour(1.0f);
  float factor = 1.0f;
  if (const tinygltf::Value* x = extensionOf(g, "KHR_materials_specular")) {
    factor = std::clamp(float(numberOr(*x, "specularFactor", -1, 1.0)), 0.0f, 1.0f);
    for (int k = 0; k < 3; ++k) colour[k] = std::max(float(numberOr(*x, "specularColorFactor", k, 1.0)), 0.0f);
    if (x->Has("specularTexture") || x->Has("specularColorTexture"))
      warn("KHR_materials_specular's textures not read: drawn with its factors alone");
  }
  return {glm::min(glm::vec3(f0) * colour, glm::vec3(1.0f)) * factor, factor};
}

// The mean of a metallic-roughness texture's G (roughness) and B
// (metallic), which multiply the factors, until the texture is drawn per
// texel: a uniform texture is drawn exactly, a patterned one as its mean.
glm::vec2 meanRoughnessMetallic(const Image& image) {
  glm::dvec2 sum(0.0);
  const size_t n = size_t(image.width) * size_t(image.height);
  for (size_t i = 0; i < n; ++i) sum += glm::dvec2(image.bytes[4 * i + 1], image.bytes[4 * i + 2]) / 255.0;
  return glm::vec2(sum / double(std::max<size_t>(n, 1)));
}

// An image tinygltf decoded, as sRGB texels (glTF's base colour is sRGB).
std::shared_ptr<const Image> texelsOf(const tinygltf::Image& g) {
  const int w = g.width, h = g.height, c = g.component, bytes = g.bits == 16 ? 2 : 1;
  if (w <= 0 || h <= 0 || c < 1 || c > 4 || g.image.size() < size_t(w) * h * c * bytes) return nullptr;
  auto img = std::make_shared<Image>(w, h, PixelType::Srgb8);
  for (size_t i = 0; i < size_t(w) * h; ++i) {
    // 16-bit samples: their high byte (little-endian).
    auto sample = [&](int k) { return g.image[(i * c + size_t(k)) * bytes + (bytes - 1)]; };
    uint8_t* out = &img->bytes[4 * i];
    out[0] = sample(0);
    out[1] = c >= 3 ? sample(1) : out[0];
    out[2] = c >= 3 ? sample(2) : out[0];
    out[3] = c == 4 ? sample(3) : c == 2 ? sample(1) : 255;
  }
  return img;
}

// The mean of an sRGB image's texels in linear light.
glm::vec3 meanLinearColor(const Image& image) {
  glm::dvec3 sum(0.0);
  const size_t n = size_t(image.width) * size_t(image.height);
  for (size_t i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) sum[k] += linearOfSrgb8(image.bytes[4 * i + size_t(k)]);
  return glm::vec3(sum / double(std::max<size_t>(n, 1)));
}

const tinygltf::Value* textureTransform(const tinygltf::TextureInfo& t) {
  const auto it = t.extensions.find("KHR_texture_transform");
  return it != t.extensions.end() && it->second.IsObject() ? &it->second : nullptr;
}

// KHR_texture_transform of a texture reference as a matrix on glTF's
// (u, v): T(offset) R(rotation) S(scale), as the extension defines it.
glm::mat3 uvTransformOf(const tinygltf::TextureInfo& t) {
  const tinygltf::Value* x = textureTransform(t);
  if (!x) return glm::mat3(1.0f);
  const float r = float(numberOr(*x, "rotation", -1, 0.0)), c = std::cos(r), s = std::sin(r);
  const glm::mat3 translation(1, 0, 0, 0, 1, 0, float(numberOr(*x, "offset", 0, 0.0)), float(numberOr(*x, "offset", 1, 0.0)), 1);
  const glm::mat3 rotation(c, -s, 0, s, c, 0, 0, 0, 1);  // u' = c u + s v, v' = c v - s u (the ratified text's)
  const glm::mat3 scale(float(numberOr(*x, "scale", 0, 1.0)), 0, 0, 0, float(numberOr(*x, "scale", 1, 1.0)), 0, 0, 0, 1);
  return translation * rotation * scale;
}

// The TEXCOORD_n a texture reference reads: KHR_texture_transform's
// texCoord where it has one (the extension overrides), else its own.
int uvSetOf(const tinygltf::TextureInfo& t) {
  const tinygltf::Value* x = textureTransform(t);
  const double set = x ? numberOr(*x, "texCoord", -1, t.texCoord) : t.texCoord;
  return set >= 0.0 && set < 8.0 ? int(set) : 0;
}

}  // namespace

double numberOr(const tinygltf::Value& object, const char* key, int index, double fallback) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& v = object.Get(key);
  const tinygltf::Value& n = index < 0 ? v : v.IsArray() && size_t(index) < v.ArrayLen() ? v.Get(index) : v;
  return n.IsNumber() && std::isfinite(n.GetNumberAsDouble()) ? n.GetNumberAsDouble() : fallback;
}

// The texture whose coordinates a material's vertices carry: the base
// colour's, or the emission's where there is no base colour texture.
const tinygltf::TextureInfo& placedTexture(const tinygltf::Material& g) {
  const tinygltf::TextureInfo& base = g.pbrMetallicRoughness.baseColorTexture;
  return base.index < 0 && g.emissiveTexture.index >= 0 ? g.emissiveTexture : base;
}

void GltfReader::readMaterials() {
  for (size_t i = 0; i < model_.materials.size(); ++i) {
    const tinygltf::TextureInfo& placed = placedTexture(model_.materials[i]);
    hidden_.push_back(false);
    uvTransforms_.push_back(uvTransformOf(placed));
    uvSets_.push_back(placed.index >= 0 ? uvSetOf(placed) : 0);
    scene_.materials.push_back(material(i));
  }
}

Material GltfReader::material(size_t i) {
  const tinygltf::Material& g = model_.materials[i];
  Material m;
  m.name = g.name.empty() ? "material " + std::to_string(i) : g.name;
  m.twoSided = g.doubleSided;
  const tinygltf::TextureInfo& t = g.pbrMetallicRoughness.baseColorTexture;
  if (t.index >= 0) {
    const int source = textureSource(t);
    m.textureImage = texelsOf(model_.images[size_t(source)]);
    if (m.textureImage)
      m.texture = path_ + "#image" + std::to_string(source);
    else
      warn_("image " + std::to_string(source) + " could not be decoded: drawn untextured");
  }
  metallicRoughness(g, m);
  if (g.alphaMode == "BLEND") warn_("alphaMode BLEND drawn opaque");
  if (g.alphaMode == "MASK") mask(g, m);
  emission(g, i, m);
  if (g.extensions.count("KHR_materials_unlit")) unlit(g, m);
  return m;
}

// pbrMetallicRoughness as our Ggx material, with KHR_materials_ior and
// KHR_materials_specular setting the dielectric's F0 and F90. A metal's F0
// is its base colour, which the base colour texture tints; the highlight
// passes do not sample that texture yet, so the metal's share of F0 takes
// the texture's mean colour (said once).
void GltfReader::metallicRoughness(const tinygltf::Material& g, Material& m) {
  const auto& pbr = g.pbrMetallicRoughness;
  float metallic = finiteOr(pbr.metallicFactor, 1.0f), roughness = finiteOr(pbr.roughnessFactor, 1.0f);
  if (pbr.metallicRoughnessTexture.index >= 0) {
    const int source = textureSource(pbr.metallicRoughnessTexture);
    if (const std::shared_ptr<const Image> image = texelsOf(model_.images[size_t(source)])) {
      const glm::vec2 mean = meanRoughnessMetallic(*image);
      roughness *= mean.x, metallic *= mean.y;
    }
  }
  const auto [f0, f90] = dielectricOf(g, warn_);
  const glm::vec3 base = factor3(pbr.baseColorFactor, glm::vec3(1.0f));
  m.setMetallicRoughness(base, metallic, roughness, f0, f90);
  if (m.textureImage && metallic > 0.0f) {
    m.specular = glm::mix(f0, glm::clamp(base, 0.0f, 1.0f) * meanLinearColor(*m.textureImage), std::min(metallic, 1.0f));
    warn_("a metal's base colour texture tints its highlight by the texture's mean colour");
  }
}

// KHR_materials_unlit: the base colour (times its texture and the vertex
// colours) as it is, lit by nothing and giving off nothing more.
void GltfReader::unlit(const tinygltf::Material& g, Material& m) {
  const auto& f = g.pbrMetallicRoughness.baseColorFactor;
  const glm::vec3 base = f.size() >= 3 ? glm::vec3(float(f[0]), float(f[1]), float(f[2])) : glm::vec3(1.0f);
  m.unlit = true;
  m.diffuse = glm::clamp(base, 0.0f, 1.0f);
  m.specular = m.emission = glm::vec3(0.0f);
  m.emissionTexture.clear();
  m.emissionImage.reset();
}

// alphaMode MASK: alpha is baseColorFactor's times the texture's (COLOR_0's
// alpha is not kept). Untextured, the whole material is in or out.
void GltfReader::mask(const tinygltf::Material& g, Material& m) {
  const auto& factor = g.pbrMetallicRoughness.baseColorFactor;
  const double a = factor.size() == 4 && std::isfinite(factor[3]) ? std::clamp(factor[3], 0.0, 1.0) : 1.0;
  const double cutoff = std::isfinite(g.alphaCutoff) ? std::clamp(g.alphaCutoff, 0.0, 1.0) : 0.5;
  if (!m.textureImage) {
    hidden_.back() = a < cutoff;
    return;
  }
  // texel alpha * a < cutoff  <=>  texel alpha < cutoff / a
  m.alphaCutoff = a > 0.0 ? float(std::min(cutoff / a, 2.0)) : 2.0f;
}

// The image a texture reference samples, checked.
int GltfReader::textureSource(const tinygltf::TextureInfo& t) {
  if (t.index < 0 || size_t(t.index) >= model_.textures.size()) fail(path_, "texture " + std::to_string(t.index) + " does not exist");
  const tinygltf::Texture& texture = model_.textures[size_t(t.index)];
  if (texture.sampler >= 0 && size_t(texture.sampler) < model_.samplers.size()) {
    const tinygltf::Sampler& wrap = model_.samplers[size_t(texture.sampler)];
    if (wrap.wrapS != TINYGLTF_TEXTURE_WRAP_REPEAT || wrap.wrapT != TINYGLTF_TEXTURE_WRAP_REPEAT)
      warn_("texture wrap modes other than REPEAT drawn as REPEAT");
  }
  if (texture.source < 0 || size_t(texture.source) >= model_.images.size())
    fail(path_, "texture " + std::to_string(t.index) + " has no image");
  return texture.source;
}

// emissiveFactor (linear, times KHR_materials_emissive_strength) and
// emissiveTexture, per texel on the coordinates the vertices carry (the
// base colour texture's). An emission texture on other coordinates than
// those would need a second set per vertex: it is drawn as its mean, right
// for a uniform glow, an average for a patterned one (said once).
void GltfReader::emission(const tinygltf::Material& g, size_t material, Material& m) {
  glm::vec3 e(0.0f);
  if (g.emissiveFactor.size() == 3)
    e = glm::vec3(float(g.emissiveFactor[0]), float(g.emissiveFactor[1]), float(g.emissiveFactor[2]));
  if (const auto s = g.extensions.find("KHR_materials_emissive_strength"); s != g.extensions.end())
    e *= float(numberOr(s->second, "emissiveStrength", -1, 1.0));
  if (!(e.x > 0.0f || e.y > 0.0f || e.z > 0.0f)) return;  // NaN too
  m.emission = e;  // unclamped: KHR_materials_emissive_strength may take it past 1
  const tinygltf::TextureInfo& t = g.emissiveTexture;
  if (t.index < 0) return;
  const int source = textureSource(t);
  const std::shared_ptr<const Image> image = texelsOf(model_.images[size_t(source)]);
  if (!image) {
    warn_("image " + std::to_string(source) + " could not be decoded: emission drawn untextured");
    return;
  }
  if (uvSetOf(t) == uvSets_[material] && uvTransformOf(t) == uvTransforms_[material]) {
    m.emissionTexture = path_ + "#image" + std::to_string(source);
    m.emissionImage = image;
    return;
  }
  m.emission = e * meanLinearColor(*image);
  warn_("emissiveTexture on other coordinates than baseColorTexture drawn as its mean colour");
}

}  // namespace mvr::gltf
