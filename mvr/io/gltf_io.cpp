#include "mvr/io/gltf_io.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "mvr/color.h"
#include "mvr/error.h"
#include "mvr/image.h"
#include "mvr/io/load_warnings.h"
#include "mvr/io/mesh_check.h"

namespace mvr {
namespace {

// Triangles one file may expand to (instancing can multiply a small file).
constexpr size_t kMaxTriangles = size_t(1) << 28;

size_t componentBytes(int type) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

// One accessor's elements, checked against its buffer once: up to four
// components each, as floats (normalized integers scaled as the spec
// says) or as unsigned indices.
class Accessor {
 public:
  Accessor(const tinygltf::Model& m, int index, const std::string& where) : where_(where) {
    if (index < 0 || size_t(index) >= m.accessors.size()) fail(where, "accessor " + std::to_string(index) + " does not exist");
    const tinygltf::Accessor& a = m.accessors[size_t(index)];
    if (a.sparse.isSparse) fail(where, "sparse accessors are not read");
    type_ = a.componentType, normalized_ = a.normalized, count_ = a.count;
    components_ = a.type == TINYGLTF_TYPE_SCALAR ? 1 : a.type == TINYGLTF_TYPE_VEC2 ? 2
                  : a.type == TINYGLTF_TYPE_VEC3 ? 3 : a.type == TINYGLTF_TYPE_VEC4 ? 4
                  : a.type == TINYGLTF_TYPE_MAT4 ? 16 : 0;
    const size_t bytes = componentBytes(type_);
    if (!components_ || !bytes) fail(where, "accessor " + std::to_string(index) + " has a type we do not read");
    if (a.bufferView < 0) return;  // all zeros
    if (size_t(a.bufferView) >= m.bufferViews.size()) fail(where, "buffer view " + std::to_string(a.bufferView) + " does not exist");
    const tinygltf::BufferView& v = m.bufferViews[size_t(a.bufferView)];
    if (v.buffer < 0 || size_t(v.buffer) >= m.buffers.size()) fail(where, "buffer " + std::to_string(v.buffer) + " does not exist");
    const std::vector<unsigned char>& data = m.buffers[size_t(v.buffer)].data;
    const size_t element = bytes * size_t(components_);
    stride_ = v.byteStride ? v.byteStride : element;
    const size_t start = v.byteOffset + a.byteOffset;
    if (v.byteOffset > data.size() || v.byteLength > data.size() - v.byteOffset ||
        (count_ && (a.byteOffset > v.byteLength || (count_ - 1) > (v.byteLength - a.byteOffset) / stride_ ||
                    (count_ - 1) * stride_ + element > v.byteLength - a.byteOffset)))
      fail(where, "accessor " + std::to_string(index) + " reaches past its buffer");
    data_ = data.data() + start;
  }

  size_t count() const { return count_; }
  int components() const { return components_; }

  glm::vec4 at(size_t k) const {
    glm::vec4 out(0.0f);
    if (!data_) return out;
    const unsigned char* p = data_ + k * stride_;
    for (int c = 0; c < std::min(components_, 4); ++c) out[c] = component(p, c);
    return out;
  }
  // A MAT4 accessor's element (column-major, as glTF's).
  glm::mat4 matrix(size_t k) const {
    if (components_ != 16 || type_ != TINYGLTF_COMPONENT_TYPE_FLOAT) fail(where_, "a matrix accessor must be float MAT4");
    glm::mat4 m(1.0f);
    if (data_)
      for (int c = 0; c < 16; ++c) m[c / 4][c % 4] = component(data_ + k * stride_, c);
    return m;
  }
  uint32_t index(size_t k) const {
    if (!data_) return 0;
    const unsigned char* p = data_ + k * stride_;
    switch (type_) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return *p;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return read<uint16_t>(p);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return read<uint32_t>(p);
      default: fail(where_, "indices must be unsigned integers");
    }
  }

 private:
  template <class T>
  static T read(const unsigned char* p) {
    T v;
    std::memcpy(&v, p, sizeof v);
    return v;
  }
  float component(const unsigned char* p, int c) const {
    switch (type_) {
      case TINYGLTF_COMPONENT_TYPE_FLOAT: return read<float>(p + 4 * c);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return scaled(float(p[c]), 255.0f);
      case TINYGLTF_COMPONENT_TYPE_BYTE: return std::max(scaled(float(int8_t(p[c])), 127.0f), -1.0f);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return scaled(float(read<uint16_t>(p + 2 * c)), 65535.0f);
      case TINYGLTF_COMPONENT_TYPE_SHORT: return std::max(scaled(float(read<int16_t>(p + 2 * c)), 32767.0f), -1.0f);
      default: return float(read<uint32_t>(p + 4 * c));
    }
  }
  float scaled(float v, float max) const { return normalized_ ? v / max : v; }

  std::string where_;
  int type_ = 0, components_ = 0;
  bool normalized_ = false;
  size_t count_ = 0, stride_ = 0;
  const unsigned char* data_ = nullptr;
};

glm::mat4 localTransform(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) {
    glm::dmat4 m;
    std::copy(n.matrix.begin(), n.matrix.end(), glm::value_ptr(m));  // column-major, as glTF's
    return glm::mat4(m);
  }
  glm::dmat4 m(1.0);
  if (n.translation.size() == 3) m = glm::translate(m, glm::dvec3(n.translation[0], n.translation[1], n.translation[2]));
  if (n.rotation.size() == 4)
    m *= glm::mat4_cast(glm::normalize(glm::dquat(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2])));
  if (n.scale.size() == 3) m = glm::scale(m, glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
  return glm::mat4(m);
}

// glTF's metallic-roughness as our Blinn-Phong material. The lobe: a
// Beckmann distribution of roughness alpha = roughness^2 is matched by a
// Blinn-Phong exponent 2 / alpha^2 - 2 (Walter et al. 2007); its colour is
// the Fresnel reflectance at normal incidence, F0 = mix(0.04, base,
// metallic), and the diffuse part base (1 - metallic). A lobe wider than
// exponent 1 (roughness above 0.84) is diffuse to our model: it is
// dropped, no view-dependent pass is planned for it, and the surface keeps
// its base colour as diffuse (a rough metal's look; glTF's defaults,
// metallic 1 and roughness 1, would otherwise be black).
Material materialOf(const tinygltf::Material& g, size_t index) {
  Material m;
  m.name = g.name.empty() ? "material " + std::to_string(index) : g.name;
  const auto& pbr = g.pbrMetallicRoughness;
  const glm::vec3 base = pbr.baseColorFactor.size() >= 3
                             ? glm::vec3(float(pbr.baseColorFactor[0]), float(pbr.baseColorFactor[1]),
                                         float(pbr.baseColorFactor[2]))
                             : glm::vec3(1.0f);
  const float metallic = std::clamp(float(pbr.metallicFactor), 0.0f, 1.0f);
  const float roughness = std::clamp(float(pbr.roughnessFactor), 0.0f, 1.0f);
  const float alpha = std::max(roughness * roughness, 1e-3f);
  const float exponent = 2.0f / (alpha * alpha) - 2.0f;
  m.diffuse = glm::clamp(base, 0.0f, 1.0f);
  if (exponent >= 1.0f) {
    m.shininess = std::min(exponent, 1e4f);
    m.specular = glm::mix(glm::vec3(0.04f), m.diffuse, metallic);
    m.diffuse *= 1.0f - metallic;
  }
  m.twoSided = g.doubleSided;
  return m;
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

double numberOr(const tinygltf::Value& object, const char* key, int index, double fallback) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& v = object.Get(key);
  const tinygltf::Value& n = index < 0 ? v : v.IsArray() && size_t(index) < v.ArrayLen() ? v.Get(index) : v;
  return n.IsNumber() && std::isfinite(n.GetNumberAsDouble()) ? n.GetNumberAsDouble() : fallback;
}

// KHR_texture_transform of a texture reference as a matrix on glTF's
// (u, v): T(offset) R(rotation) S(scale), as the extension defines it.
glm::mat3 uvTransformOf(const tinygltf::TextureInfo& t) {
  const auto it = t.extensions.find("KHR_texture_transform");
  if (it == t.extensions.end() || !it->second.IsObject()) return glm::mat3(1.0f);
  const tinygltf::Value& x = it->second;
  const float r = float(numberOr(x, "rotation", -1, 0.0)), c = std::cos(r), s = std::sin(r);
  const glm::mat3 translation(1, 0, 0, 0, 1, 0, float(numberOr(x, "offset", 0, 0.0)), float(numberOr(x, "offset", 1, 0.0)), 1);
  const glm::mat3 rotation(c, -s, 0, s, c, 0, 0, 0, 1);  // u' = c u + s v, v' = c v - s u (the ratified text's)
  const glm::mat3 scale(float(numberOr(x, "scale", 0, 1.0)), 0, 0, 0, float(numberOr(x, "scale", 1, 1.0)), 0, 0, 0, 1);
  return translation * rotation * scale;
}

class GltfReader {
 public:
  GltfReader(const tinygltf::Model& model, const std::string& path) : model_(model), path_(path) {}

  Scene read() {
    for (size_t i = 0; i < model_.materials.size(); ++i) {
      hidden_.push_back(false);
      scene_.materials.push_back(material(i));
      uvTransforms_.push_back(uvTransformOf(model_.materials[i].pbrMetallicRoughness.baseColorTexture));
    }
    for (const tinygltf::Mesh& m : model_.meshes)
      for (const tinygltf::Primitive& p : m.primitives) anyUv_ = anyUv_ || p.attributes.count("TEXCOORD_0");
    std::vector<int> roots;
    if (!model_.scenes.empty()) {
      const size_t s = model_.defaultScene >= 0 && size_t(model_.defaultScene) < model_.scenes.size()
                           ? size_t(model_.defaultScene) : 0;
      roots = model_.scenes[s].nodes;
    } else {
      std::vector<bool> child(model_.nodes.size(), false);
      for (const tinygltf::Node& n : model_.nodes)
        for (int c : n.children)
          if (c >= 0 && size_t(c) < child.size()) child[size_t(c)] = true;
      for (size_t i = 0; i < child.size(); ++i)
        if (!child[i]) roots.push_back(int(i));
    }
    for (const std::string& e : model_.extensionsRequired)
      if (e != "KHR_texture_transform" && e != "KHR_lights_punctual" && e != "KHR_mesh_quantization")
        warn_("requires the extension " + e + ", which is not read: drawn without it");
    bool morphs = false;
    for (const tinygltf::Mesh& m : model_.meshes)
      for (const tinygltf::Primitive& p : m.primitives) morphs = morphs || !p.targets.empty();
    if (!model_.animations.empty() || !model_.skins.empty() || morphs) animation_ = std::make_shared<SceneAnimation>();
    onPath_.assign(model_.nodes.size(), false);
    for (int r : roots) node(r, glm::mat4(1.0f), -1);
    if (scene_.triangles.empty()) fail(path_, "glTF scene has no triangles");
    if (animation_) {
      readSkins();
      // Skins and morph weights at rest give the shape the file shows.
      if (!model_.skins.empty() || morphs) animation_->pose(scene_, 0.0, -2, glm::mat4(1.0f));
      readClips();
    }
    addLights();
    scene_.source = path_;
    return std::move(scene_);
  }

 private:
  Material material(size_t i) {
    const tinygltf::Material& g = model_.materials[i];
    Material m = materialOf(g, i);
    const tinygltf::TextureInfo& t = g.pbrMetallicRoughness.baseColorTexture;
    if (t.index >= 0) {
      const int source = textureSource(t, "baseColorTexture");
      m.textureImage = texelsOf(model_.images[size_t(source)]);
      if (m.textureImage)
        m.texture = path_ + "#image" + std::to_string(source);
      else
        warn_("image " + std::to_string(source) + " could not be decoded: drawn untextured");
    }
    if (g.alphaMode == "BLEND") warn_("alphaMode BLEND drawn opaque");
    if (g.alphaMode == "MASK") mask(g, m);
    m.emission = emission(g);
    return m;
  }

  // alphaMode MASK: alpha is baseColorFactor's times the texture's (COLOR_0's
  // alpha is not kept). Untextured, the whole material is in or out.
  void mask(const tinygltf::Material& g, Material& m) {
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
  int textureSource(const tinygltf::TextureInfo& t, const std::string& slot) {
    if (size_t(t.index) >= model_.textures.size()) fail(path_, "texture " + std::to_string(t.index) + " does not exist");
    const tinygltf::Texture& texture = model_.textures[size_t(t.index)];
    if (texture.sampler >= 0 && size_t(texture.sampler) < model_.samplers.size()) {
      const tinygltf::Sampler& wrap = model_.samplers[size_t(texture.sampler)];
      if (wrap.wrapS != TINYGLTF_TEXTURE_WRAP_REPEAT || wrap.wrapT != TINYGLTF_TEXTURE_WRAP_REPEAT)
        warn_("texture wrap modes other than REPEAT drawn as REPEAT");
    }
    if (texture.source < 0 || size_t(texture.source) >= model_.images.size())
      fail(path_, "texture " + std::to_string(t.index) + " has no image");
    if (t.texCoord != 0) warn_(slot + " on TEXCOORD_" + std::to_string(t.texCoord) + " read with TEXCOORD_0");
    return texture.source;
  }

  // emissiveFactor (linear, times KHR_materials_emissive_strength) and
  // emissiveTexture. We carry one emission colour per material, so a
  // texture's is its mean: right for a uniform glow, an average for a
  // patterned one (said once in the warnings).
  glm::vec3 emission(const tinygltf::Material& g) {
    glm::vec3 e(0.0f);
    if (g.emissiveFactor.size() == 3)
      e = glm::vec3(float(g.emissiveFactor[0]), float(g.emissiveFactor[1]), float(g.emissiveFactor[2]));
    if (const auto s = g.extensions.find("KHR_materials_emissive_strength"); s != g.extensions.end())
      e *= float(numberOr(s->second, "emissiveStrength", -1, 1.0));
    if (!(e.x > 0.0f || e.y > 0.0f || e.z > 0.0f)) return glm::vec3(0.0f);  // NaN too
    if (g.emissiveTexture.index >= 0) {
      const int source = textureSource(g.emissiveTexture, "emissiveTexture");
      if (const std::shared_ptr<const Image> image = texelsOf(model_.images[size_t(source)])) {
        e *= meanLinearColor(*image);
        warn_("emissiveTexture drawn as its mean colour");
      }
    }
    return glm::clamp(e, 0.0f, 1.0f);
  }

  // parentSlot: the parent's place in the animation's node list (-1: a root).
  void node(int index, const glm::mat4& parent, int parentSlot) {
    if (index < 0 || size_t(index) >= model_.nodes.size()) fail(path_, "node " + std::to_string(index) + " does not exist");
    if (onPath_[size_t(index)]) fail(path_, "node " + std::to_string(index) + " is its own ancestor");
    onPath_[size_t(index)] = true;
    const tinygltf::Node& n = model_.nodes[size_t(index)];
    const glm::mat4 world = parent * localTransform(n);
    const int slot = animation_ ? animatedNode(index, parentSlot) : -1;
    currentNode_ = index;
    if (n.mesh >= 0) {
      if (size_t(n.mesh) >= model_.meshes.size()) fail(path_, "mesh " + std::to_string(n.mesh) + " does not exist");
      for (const tinygltf::Primitive& p : model_.meshes[size_t(n.mesh)].primitives) {
        if (animation_) {
          instance_ = &animation_->instances.emplace_back();
          instance_->node = slot;
          instance_->first = uint32_t(scene_.positions.size());
          instance_->skin = n.skin;  // the file's; ours after readSkins
        }
        primitive(p, world);
        instance_ = nullptr;
      }
    }
    if (n.camera >= 0) camera(n, world);
    if (const auto light = n.extensions.find("KHR_lights_punctual"); light != n.extensions.end())
      placeLight(light->second, world);
    for (int c : n.children) node(c, world, slot);
    onPath_[size_t(index)] = false;
  }

  // The node in the animation's list (parents before children), with its
  // rest transform; slots_ maps the file's node to its places.
  int animatedNode(int index, int parentSlot) {
    const tinygltf::Node& n = model_.nodes[size_t(index)];
    AnimatedNode a;
    a.parent = parentSlot;
    if (n.matrix.size() == 16) {
      a.hasMatrix = true;
      a.matrix = localTransform(n);
    } else {
      if (n.translation.size() == 3) a.translation = glm::vec3(float(n.translation[0]), float(n.translation[1]), float(n.translation[2]));
      if (n.rotation.size() == 4)
        a.rotation = glm::normalize(glm::quat(float(n.rotation[3]), float(n.rotation[0]), float(n.rotation[1]), float(n.rotation[2])));
      if (n.scale.size() == 3) a.scale = glm::vec3(float(n.scale[0]), float(n.scale[1]), float(n.scale[2]));
    }
    // Morph weights: the node's, else its mesh's.
    const std::vector<double>* w = &n.weights;
    if (w->empty() && n.mesh >= 0 && size_t(n.mesh) < model_.meshes.size()) w = &model_.meshes[size_t(n.mesh)].weights;
    for (double x : *w) a.weights.push_back(std::isfinite(x) ? float(x) : 0.0f);
    const int slot = int(animation_->nodes.size());
    animation_->nodes.push_back(a);
    slots_[index].push_back(slot);
    return slot;
  }

  // The skins the instances use, with their joints' places in the node
  // list. A joint outside the scene drawn cannot move: its skin's meshes
  // are drawn rigid, as their nodes place them.
  void readSkins() {
    std::map<int, int> ours;  // the file's skin, ours (-1: not usable)
    for (AnimatedInstance& inst : animation_->instances) {
      if (inst.skin < 0) continue;
      if (size_t(inst.skin) >= model_.skins.size()) fail(path_, "skin " + std::to_string(inst.skin) + " does not exist");
      if (inst.joints.empty()) {
        inst.skin = -1;  // a primitive without JOINTS_0
        continue;
      }
      auto [it, added] = ours.emplace(inst.skin, -1);
      if (added) it->second = skin(size_t(inst.skin));
      inst.skin = it->second;
    }
  }

  int skin(size_t index) {
    const tinygltf::Skin& g = model_.skins[index];
    AnimatedSkin s;
    std::unique_ptr<Accessor> inverse;
    if (g.inverseBindMatrices >= 0) {
      inverse = std::make_unique<Accessor>(model_, g.inverseBindMatrices, path_);
      if (inverse->count() < g.joints.size()) fail(path_, "skin " + std::to_string(index) + " has fewer inverse bind matrices than joints");
    }
    for (size_t j = 0; j < g.joints.size(); ++j) {
      const auto where = slots_.find(g.joints[j]);
      if (where == slots_.end()) {
        warn_("a skin's joint is not in the scene drawn: its meshes drawn unskinned");
        return -1;
      }
      s.joints.push_back(where->second.front());
      s.inverseBind.push_back(inverse ? inverse->matrix(j) : glm::mat4(1.0f));
    }
    animation_->skins.push_back(std::move(s));
    return int(animation_->skins.size()) - 1;
  }

  // The file's animations as clips of node TRS and morph weight channels.
  void readClips() {
    for (size_t i = 0; i < model_.animations.size(); ++i) {
      const tinygltf::Animation& g = model_.animations[i];
      AnimationClip clip;
      clip.name = g.name.empty() ? "animation " + std::to_string(i) : g.name;
      for (const tinygltf::AnimationChannel& c : g.channels) channel(g, c, clip);
      if (!clip.channels.empty()) animation_->clips.push_back(std::move(clip));
    }
    if (animation_->clips.empty()) return;
    scene_.animations.push_back(std::move(animation_));
  }

  void channel(const tinygltf::Animation& g, const tinygltf::AnimationChannel& c, AnimationClip& clip) {
    const auto path = c.target_path == "translation" ? AnimationChannel::Path::Translation
                      : c.target_path == "rotation"  ? AnimationChannel::Path::Rotation
                      : c.target_path == "scale"     ? AnimationChannel::Path::Scale
                      : c.target_path == "weights"   ? AnimationChannel::Path::Weights
                                                     : throw Error(path_ + ": animation channel of path '" +
                                                                   c.target_path.substr(0, 40) + "' is not glTF 2.0");
    if (c.sampler < 0 || size_t(c.sampler) >= g.samplers.size()) fail(path_, "animation sampler " + std::to_string(c.sampler) + " does not exist");
    const auto where = slots_.find(c.target_node);
    if (where == slots_.end()) return;  // a node outside the scene drawn
    const tinygltf::AnimationSampler& s = g.samplers[size_t(c.sampler)];
    AnimationChannel ch;
    ch.path = path;
    ch.interpolation = s.interpolation == "STEP"          ? AnimationChannel::Interpolation::Step
                       : s.interpolation == "CUBICSPLINE" ? AnimationChannel::Interpolation::CubicSpline
                                                          : AnimationChannel::Interpolation::Linear;
    const Accessor input(model_, s.input, path_), output(model_, s.output, path_);
    if (input.components() != 1) fail(path_, "animation input must be SCALAR times");
    const size_t perKey = ch.interpolation == AnimationChannel::Interpolation::CubicSpline ? 3 : 1;
    if (path == AnimationChannel::Path::Weights) {
      // SCALAR outputs, one per morph target and key part.
      const size_t keys = perKey * input.count();
      if (output.components() != 1 || keys == 0 || output.count() % keys || output.count() / keys > 4096)
        fail(path_, "animation output of weights does not match its times");
      ch.weights = int(output.count() / keys);
    }
    const size_t perValue = path == AnimationChannel::Path::Weights ? size_t(ch.weights) : 1;
    if (output.components() != (path == AnimationChannel::Path::Weights ? 1 : ch.components()))
      fail(path_, "animation output of " + c.target_path + " has the wrong type");
    if (input.count() == 0 || output.count() != perKey * perValue * input.count())
      fail(path_, "animation sampler has " + std::to_string(output.count()) + " values for " + std::to_string(input.count()) + " times");
    for (size_t k = 0; k < input.count(); ++k) {
      const float t = input.at(k).x;
      if (!std::isfinite(t) || (k > 0 && !(t > ch.times.back()))) fail(path_, "animation times must rise and be finite");
      ch.times.push_back(t);
    }
    for (size_t k = 0; k < output.count(); ++k) {
      const glm::vec4 v = output.at(k);
      for (int j = 0; j < output.components(); ++j) {
        if (!std::isfinite(v[j])) fail(path_, "animation values must be finite");
        ch.values.push_back(v[j]);
      }
    }
    for (int slot : where->second) {
      ch.node = slot;
      clip.channels.push_back(ch);
    }
  }

  void camera(const tinygltf::Node& n, const glm::mat4& world) {
    if (size_t(n.camera) >= model_.cameras.size()) fail(path_, "camera " + std::to_string(n.camera) + " does not exist");
    const tinygltf::Camera& c = model_.cameras[size_t(n.camera)];
    if (c.type != "perspective") {
      warn_("orthographic cameras skipped");
      return;
    }
    const double yfov = c.perspective.yfov;
    if (!(yfov > 0.0 && yfov < 3.1)) fail(path_, "camera " + std::to_string(n.camera) + " has a yfov outside (0, 3.1)");
    const std::string name = !c.name.empty() ? c.name : !n.name.empty() ? n.name : "camera " + std::to_string(n.camera);
    scene_.fileCameras.push_back({name, world, yfov});
  }

  void placeLight(const tinygltf::Value& ext, const glm::mat4& world) {
    const int index = ext.Has("light") && ext.Get("light").IsNumber() ? ext.Get("light").GetNumberAsInt() : -1;
    if (index < 0 || size_t(index) >= model_.lights.size()) fail(path_, "light " + std::to_string(index) + " does not exist");
    placedLights_.emplace_back(size_t(index), world);
  }

  // KHR_lights_punctual's physical units (lux; candela) as our colours in
  // [0, 1]: each light's illuminance at the centre of the scene's bounds
  // (our point lights do not fall off, so a point or spot light's is taken
  // there), scaled so that they sum to 1. The lights keep their balance;
  // the exposure is ours, as a camera's automatic exposure would be.
  void addLights() {
    const glm::vec3 centre = scene_.bounds().center();
    std::vector<std::pair<double, Light>> lit;  // illuminance, light
    for (const auto& [index, world] : placedLights_) {
      const tinygltf::Light& g = model_.lights[index];
      Light light;
      if (g.color.size() == 3)
        light.color = glm::clamp(glm::vec3(float(g.color[0]), float(g.color[1]), float(g.color[2])), 0.0f, 1.0f);
      const double intensity = std::isfinite(g.intensity) ? std::max(g.intensity, 0.0) : 0.0;
      double illuminance = intensity;
      if (g.type == "directional") {
        const glm::vec3 d = glm::mat3(world) * glm::vec3(0.0f, 0.0f, -1.0f);
        light.vector = glm::length(d) > 0.0f ? glm::normalize(d) : glm::vec3(0.0f, 0.0f, -1.0f);
      } else {
        if (g.type == "spot") warn_("spot lights drawn as point lights (their cones not modelled)");
        light.type = Light::Type::Point;
        light.vector = glm::vec3(world * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
        const double d = glm::distance(glm::dvec3(light.vector), glm::dvec3(centre));
        illuminance = intensity / std::max(d * d, 1e-12);
      }
      if (g.range > 0.0) warn_("light ranges not modelled: lights do not fall off");
      if (illuminance > 0.0 && std::isfinite(illuminance)) lit.emplace_back(illuminance, light);
    }
    if (lit.empty()) {
      if (!placedLights_.empty()) warn_("its lights have no intensity: the default light is used");
      return;
    }
    std::stable_sort(lit.begin(), lit.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
    if (lit.size() > size_t(kMaxLights)) {
      warn_(std::to_string(lit.size()) + " lights: the " + std::to_string(kMaxLights) + " brightest are used");
      lit.resize(size_t(kMaxLights));
    }
    double sum = 0.0;
    for (const auto& l : lit) sum += l.first;
    for (auto& [illuminance, light] : lit) {
      light.color *= float(illuminance / sum);
      scene_.lights.push_back(light);
    }
  }

  // The primitive's triangles as corner indices, by its mode.
  std::vector<glm::uvec3> corners(const tinygltf::Primitive& p, size_t vertices) {
    std::vector<uint32_t> idx;
    if (p.indices >= 0) {
      const Accessor a(model_, p.indices, path_);
      idx.resize(a.count());
      for (size_t k = 0; k < idx.size(); ++k)
        if ((idx[k] = a.index(k)) >= vertices) fail(path_, "index " + std::to_string(idx[k]) + " beyond the vertices");
    } else {
      idx.resize(vertices);
      for (size_t k = 0; k < vertices; ++k) idx[k] = uint32_t(k);
    }
    std::vector<glm::uvec3> out;
    const size_t n = idx.size();
    if (p.mode == TINYGLTF_MODE_TRIANGLES || p.mode == -1) {
      for (size_t k = 0; k + 2 < n; k += 3) out.emplace_back(idx[k], idx[k + 1], idx[k + 2]);
    } else if (p.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
      for (size_t k = 0; k + 2 < n; ++k)
        out.emplace_back(idx[k], idx[k + 1 + k % 2], idx[k + 2 - k % 2]);
    } else if (p.mode == TINYGLTF_MODE_TRIANGLE_FAN) {
      for (size_t k = 0; k + 2 < n; ++k) out.emplace_back(idx[k + 1], idx[k + 2], idx[0]);
    }
    return out;
  }

  const Accessor* attribute(const tinygltf::Primitive& p, const char* name, std::unique_ptr<Accessor>& holder) {
    auto it = p.attributes.find(name);
    if (it == p.attributes.end()) return nullptr;
    holder = std::make_unique<Accessor>(model_, it->second, path_);
    return holder.get();
  }

  void primitive(const tinygltf::Primitive& p, const glm::mat4& world) {
    if (p.mode != -1 && p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        p.mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      warn_("points and lines skipped");
      return;
    }
    std::unique_ptr<Accessor> positionHold, normalHold, uvHold, colorHold;
    const Accessor* position = attribute(p, "POSITION", positionHold);
    if (!position) {
      warn_("a primitive without POSITION skipped");
      return;
    }
    if (position->components() != 3) fail(path_, "POSITION must be VEC3");
    const Accessor* normal = attribute(p, "NORMAL", normalHold);
    const Accessor* uv = attribute(p, "TEXCOORD_0", uvHold);
    const Accessor* color = attribute(p, "COLOR_0", colorHold);
    for (const Accessor* a : {normal, uv, color})
      if (a && a->count() != position->count()) fail(path_, "a primitive's attributes differ in count");
    if (normal && normal->components() != 3) fail(path_, "NORMAL must be VEC3");
    const Deformation deform = deformation(p, position->count(), normal != nullptr);
    std::vector<glm::uvec3> tris = corners(p, position->count());
    if (scene_.triangles.size() + tris.size() > kMaxTriangles) fail(path_, "more than 2^28 triangles");
    reserve(normal ? position->count() : 3 * tris.size(), tris.size());
    const uint32_t materialId = p.material >= 0 && size_t(p.material) < scene_.materials.size() ? uint32_t(p.material)
                                                                                                 : defaultMaterial();
    if (materialId < hidden_.size() && hidden_[materialId]) return;  // masked out whole
    const glm::mat3 uvTransform = materialId < uvTransforms_.size() ? uvTransforms_[materialId] : glm::mat3(1.0f);
    const glm::mat3 linear(world);
    const glm::mat3 normalMatrix = glm::transpose(glm::inverse(linear));
    const bool mirrored = glm::determinant(linear) < 0.0f;
    auto vertex = [&](uint32_t k, const glm::vec3& n, const glm::vec3& local) {
      scene_.positions.push_back(glm::vec3(world * glm::vec4(glm::vec3(position->at(k)), 1.0f)));
      scene_.normals.push_back(n);
      if (instance_) {
        instance_->positions.push_back(glm::vec3(position->at(k)));
        instance_->normals.push_back(local);
        deform.add(k, *instance_);
      }
      if (anyUv_) {
        const glm::vec2 t = uv ? glm::vec2(uvTransform * glm::vec3(glm::vec2(uv->at(k)), 1.0f)) : glm::vec2(0.0f, 1.0f);
        scene_.uvs.emplace_back(t.x, 1.0f - t.y);  // glTF's v runs down the image, ours up
      }
      scene_.colors.push_back(color ? glm::clamp(glm::vec3(color->at(k)), 0.0f, 1.0f) : glm::vec3(1.0f));
    };
    auto unit = [](glm::vec3 v) {
      const float l = glm::length(v);
      return l > 0.0f && std::isfinite(l) ? v / l : glm::vec3(0.0f, 0.0f, 1.0f);
    };
    if (normal) {
      const auto base = uint32_t(scene_.positions.size());
      for (uint32_t k = 0; k < uint32_t(position->count()); ++k)
        vertex(k, unit(normalMatrix * glm::vec3(normal->at(k))), glm::vec3(normal->at(k)));
      for (glm::uvec3 t : tris) add(t + base, mirrored, materialId);
      return;
    }
    // No normals: flat ones (the spec), so each triangle its own corners.
    if (instance_) instance_->flat = true;
    for (glm::uvec3 t : tris) {
      if (mirrored) std::swap(t.y, t.z);
      const glm::vec3 a = glm::vec3(world * glm::vec4(glm::vec3(position->at(t.x)), 1.0f));
      const glm::vec3 b = glm::vec3(world * glm::vec4(glm::vec3(position->at(t.y)), 1.0f));
      const glm::vec3 c = glm::vec3(world * glm::vec4(glm::vec3(position->at(t.z)), 1.0f));
      const glm::vec3 n = unit(glm::cross(b - a, c - a));
      const glm::vec3 la(position->at(t.x)), lb(position->at(t.y)), lc(position->at(t.z));
      // world's n in the node's space: the cross product moves by det(M) M^-T,
      // the normal matrix by M^-T.
      const glm::vec3 local = glm::cross(lb - la, lc - la) * (mirrored ? -1.0f : 1.0f);
      const auto base = uint32_t(scene_.positions.size());
      for (uint32_t k : {t.x, t.y, t.z}) vertex(k, n, local);
      add(glm::uvec3(base, base + 1, base + 2), false, materialId);
    }
  }

  // What moves a primitive's vertices besides its node: morph targets'
  // displacements and skin joints, read once and added per vertex.
  struct Deformation {
    std::string path;
    std::vector<std::unique_ptr<Accessor>> positions, normals;  // per target; null: none
    std::unique_ptr<Accessor> joints, weights;
    size_t jointCount = 0;

    void add(uint32_t k, AnimatedInstance& inst) const {
      for (size_t i = 0; i < positions.size(); ++i) {
        inst.morphPositions[i].push_back(positions[i] ? glm::vec3(positions[i]->at(k)) : glm::vec3(0.0f));
        if (normals[i]) inst.morphNormals[i].push_back(glm::vec3(normals[i]->at(k)));
      }
      if (!joints) return;
      const glm::uvec4 j(joints->at(k));
      glm::vec4 w = glm::max(weights->at(k), glm::vec4(0.0f));
      const float sum = w.x + w.y + w.z + w.w;
      // Weights should sum to 1 (the spec); a vertex without any follows its first joint.
      w = sum > 0.0f && std::isfinite(sum) ? w / sum : glm::vec4(1, 0, 0, 0);
      for (int c = 0; c < 4; ++c)
        if (w[c] > 0.0f && j[c] >= jointCount)
          throw Error(path + ": JOINTS_0 names joint " + std::to_string(j[c]) + " of a skin of " + std::to_string(jointCount));
      inst.joints.push_back(glm::u16vec4(glm::min(j, glm::uvec4(uint32_t(std::max<size_t>(jointCount, 1) - 1)))));
      inst.jointWeights.push_back(w);
    }
  };

  Deformation deformation(const tinygltf::Primitive& p, size_t count, bool hasNormals) {
    Deformation d;
    d.path = path_;
    if (!instance_) return d;
    for (const auto& target : p.targets) {
      auto accessor = [&](const char* name) -> std::unique_ptr<Accessor> {
        const auto it = target.find(name);
        if (it == target.end()) return nullptr;
        auto a = std::make_unique<Accessor>(model_, it->second, path_);
        if (a->components() != 3 || a->count() != count) fail(path_, std::string("a morph target's ") + name + " must be VEC3, one per vertex");
        return a;
      };
      d.positions.push_back(accessor("POSITION"));
      d.normals.push_back(hasNormals ? accessor("NORMAL") : nullptr);
    }
    instance_->morphPositions.resize(d.positions.size());
    instance_->morphNormals.resize(d.positions.size());
    const int skin = model_.nodes[size_t(currentNode_)].skin;
    if (skin < 0 || size_t(skin) >= model_.skins.size() || !p.attributes.count("JOINTS_0")) return d;
    if (!p.attributes.count("WEIGHTS_0")) fail(path_, "JOINTS_0 without WEIGHTS_0");
    d.joints = std::make_unique<Accessor>(model_, p.attributes.at("JOINTS_0"), path_);
    d.weights = std::make_unique<Accessor>(model_, p.attributes.at("WEIGHTS_0"), path_);
    if (d.joints->components() != 4 || d.weights->components() != 4 || d.joints->count() != count || d.weights->count() != count)
      fail(path_, "JOINTS_0 and WEIGHTS_0 must be VEC4, one per vertex");
    if (p.attributes.count("JOINTS_1")) warn_("more than four joints a vertex: the first four used");
    d.jointCount = model_.skins[size_t(skin)].joints.size();
    return d;
  }

  // Room for a primitive more, growing geometrically: a file of many
  // primitives reallocates as often as push_back would, one of a few
  // large ones not at all.
  void reserve(size_t vertices, size_t triangles) {
    auto grow = [](auto& v, size_t more) {
      if (v.size() + more > v.capacity()) v.reserve(std::max(v.size() + more, 2 * v.capacity()));
    };
    grow(scene_.positions, vertices), grow(scene_.normals, vertices), grow(scene_.colors, vertices);
    if (anyUv_) grow(scene_.uvs, vertices);
    grow(scene_.triangles, triangles), grow(scene_.materialIds, triangles);
  }

  void add(glm::uvec3 t, bool mirrored, uint32_t materialId) {
    if (t.x == t.y || t.y == t.z || t.x == t.z) {
      ++scene_.droppedFaces;
      return;
    }
    if (mirrored) std::swap(t.y, t.z);
    scene_.triangles.push_back(t);
    scene_.materialIds.push_back(materialId);
  }

  uint32_t defaultMaterial() {
    if (defaultMaterial_ < 0) {
      defaultMaterial_ = int(scene_.materials.size());
      Material m;
      m.diffuse = glm::vec3(1.0f);  // the spec's default material: white, rough
      m.twoSided = false;
      scene_.materials.push_back(m);
    }
    return uint32_t(defaultMaterial_);
  }


  const tinygltf::Model& model_;
  std::string path_;
  Scene scene_;
  std::vector<bool> onPath_;
  std::vector<std::pair<size_t, glm::mat4>> placedLights_;  // light, its node's world transform
  std::vector<glm::mat3> uvTransforms_;  // per material: its base colour texture's KHR_texture_transform
  std::vector<bool> hidden_;             // per material: masked out whole (alphaMode MASK, no texture)
  std::shared_ptr<SceneAnimation> animation_;  // when the file has animations
  AnimatedInstance* instance_ = nullptr;       // the primitive being read, when animated
  int currentNode_ = -1;                       // the node whose mesh is being read
  std::map<int, std::vector<int>> slots_;      // a file node's places in animation_->nodes
  LoadWarnings warn_{scene_, path_};
  bool anyUv_ = false;
  int defaultMaterial_ = -1;
};

std::string firstLine(const std::string& s) {
  const size_t end = s.find('\n');
  std::string line = s.substr(0, end);
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
  return line;
}

// A file's bytes mapped read-only for the life of the object.
class MappedFile {
 public:
  explicit MappedFile(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    struct stat st {};
    if (fd < 0 || ::fstat(fd, &st) != 0) {
      if (fd >= 0) ::close(fd);
      fail(path, "cannot read");
    }
    size_ = size_t(st.st_size);
    if (size_ > 0) data_ = ::mmap(nullptr, size_, PROT_READ, MAP_PRIVATE, fd, 0);
    ::close(fd);
    if (data_ == MAP_FAILED) fail(path, "cannot read");
  }
  ~MappedFile() {
    if (data_ && data_ != MAP_FAILED) ::munmap(data_, size_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  const unsigned char* bytes() const { return static_cast<const unsigned char*>(data_); }
  size_t size() const { return size_; }

 private:
  void* data_ = nullptr;
  size_t size_ = 0;
};

constexpr const char* kVersionOne = "glTF 1.0 is not read, glTF 2.0 is (re-export, or convert with a glTF 1-to-2 tool)";

// Extensions without which a file's meshes cannot be read at all.
bool isGeometryExtension(const std::string& e) {
  return e == "KHR_draco_mesh_compression" || e == "EXT_meshopt_compression";
}

std::string unreadExtension(const std::string& e) {
  return "needs the extension " + e + ", which is not read (re-export without mesh compression)";
}

// Why tinygltf refused a .gltf, where the file says it plainly: glTF 1
// ("version": "1.0", or the number 1, which tinygltf cannot read), or a
// compressed mesh tinygltf finds no data for. Empty where neither.
std::string refusal(const std::string& path) {
  if (lowerExtension(path) != ".gltf") return "";
  std::ifstream in(path);
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (!j.is_object()) return "";
  if (j.contains("asset") && j["asset"].is_object() && j["asset"].contains("version")) {
    const nlohmann::json& v = j["asset"]["version"];
    if ((v.is_number() && v.get<double>() < 2.0) || (v.is_string() && v.get<std::string>().rfind('1', 0) == 0))
      return kVersionOne;
  }
  if (j.contains("extensionsRequired") && j["extensionsRequired"].is_array())
    for (const nlohmann::json& e : j["extensionsRequired"])
      if (e.is_string() && isGeometryExtension(e.get<std::string>())) return unreadExtension(e.get<std::string>());
  return "";
}

}  // namespace

bool isGltfPath(const std::string& path) {
  const std::string ext = lowerExtension(path);
  return ext == ".gltf" || ext == ".glb";
}

Scene loadGltf(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) fail(path, "no such glTF file");
  tinygltf::TinyGLTF loader;
  tinygltf::Model model;
  std::string error, warning;
  bool ok = false;
  if (lowerExtension(path) == ".glb") {
    // Mapped, not read: tinygltf's own file read zero-fills a buffer the
    // size of the file and copies the file into it, before it copies the
    // binary chunk again into its buffer (a 1M-triangle GLB: 24 MB).
    const MappedFile file(path);
    const unsigned char* bytes = file.bytes();
    const size_t size = file.size();
    if (size > 0xffffffffu) fail(path, "GLB file over 4 GiB");
    if (size >= 8 && std::memcmp(bytes, "glTF", 4) == 0 && bytes[4] == 1 && !bytes[5] && !bytes[6] && !bytes[7])
      fail(path, kVersionOne);
    ok = loader.LoadBinaryFromMemory(&model, &error, &warning, bytes, unsigned(size),
                                     std::filesystem::path(path).parent_path().string());
  } else {
    ok = loader.LoadASCIIFromFile(&model, &error, &warning, path);
  }
  if (!ok) {
    const std::string why = refusal(path);
    fail(path, !why.empty() ? why : error.empty() ? "cannot read glTF" : firstLine(error));
  }
  if (!model.asset.version.empty() && model.asset.version[0] == '1') fail(path, kVersionOne);
  for (const std::string& e : model.extensionsRequired)
    if (isGeometryExtension(e)) fail(path, unreadExtension(e));
  Scene scene = GltfReader(model, path).read();
  if (!warning.empty()) scene.warnings.push_back(path + ": " + firstLine(warning));
  return scene;
}

}  // namespace mvr
