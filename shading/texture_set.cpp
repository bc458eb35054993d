#include "shading/texture_set.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>

#include "mvr/error.h"
#include "mvr/image.h"
#include "mvr/images/image_file.h"

namespace mvr::shading {
namespace {

int wrap(int i, int n) { return ((i % n) + n) % n; }

// The texels white, their alpha kept: multiplying by them is exact (1.0
// is exact in every filter), and the alpha still cuts.
std::shared_ptr<const Image> whiteWithAlphaOf(const Image& image) {
  auto white = std::make_shared<Image>(image.width, image.height, PixelType::Srgb8);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) white->setLinear(x, y, glm::vec4(1.0f, 1.0f, 1.0f, image.linear(x, y).a));
  return white;
}

std::shared_ptr<const Image> whiteTexel() {
  auto white = std::make_shared<Image>(1, 1, PixelType::Srgb8);
  white->setLinear(0, 0, glm::vec4(1.0f));
  return white;
}

}  // namespace

TextureSet TextureSet::load(const Scene& scene) {
  TextureSet set;
  std::map<std::string, int> layerOf;
  std::vector<std::shared_ptr<const Image>> images;  // embedded ones shared, not copied
  auto layer = [&](const std::string& name, const std::shared_ptr<const Image>& embedded) {
    auto [it, added] = layerOf.emplace(name, int(images.size()));
    if (added) images.push_back(embedded ? embedded : std::make_shared<const Image>(readImage(name)));
    return it->second;
  };
  for (const Material& m : scene.materials) {
    set.emissionLayer_.push_back(m.emissionTexture.empty() ? -1 : layer(m.emissionTexture, m.emissionImage));
    if (!m.texture.empty())
      set.materialLayer_.push_back(layer(m.texture, m.textureImage));
    else if (!m.emissionTexture.empty())
      set.materialLayer_.push_back(layer("#white", whiteTexel()));
    else
      set.materialLayer_.push_back(-1);
  }
  if (scene.exactColors)  // colours that are data: a texture only cuts them out
    for (auto& image : images) image = whiteWithAlphaOf(*image);
  set.layers_.resize(images.size());
  for (size_t i = 0; i < images.size(); ++i) set.layers_[i].levelSize = {{images[i]->width, images[i]->height}};
  set.group();
  for (size_t i = 0; i < images.size(); ++i) {
    Layer& layer = set.layers_[i];
    const Image& img = *images[i];
    // At its own size (a copy, bottom row first), or up to its group's.
    const glm::ivec2 size = set.groupSize_[size_t(layer.group)];
    layer.levelSize = {size};
    layer.levels = {resampleSrgb8(img, {0, 0, img.width, img.height}, size.x, size.y, true)};
    set.addLevels(layer);
  }
  return set;
}

// Box-filtered chain down to 1 x 1 (odd sizes drop the last texel),
// averaged in linear light. Texels are stored as GL_SRGB8_ALPHA8 stores
// them (decodeSrgb8).
void TextureSet::addLevels(Layer& layer) {
  while (layer.levelSize.back() != glm::ivec2(1)) {
    const glm::ivec2 from = layer.levelSize.back(), to = glm::max(from / 2, glm::ivec2(1));
    const std::vector<uint8_t>& src = layer.levels.back();
    std::vector<uint8_t> dst(size_t(to.x) * to.y * 4);
    for (int y = 0; y < to.y; ++y)
      for (int x = 0; x < to.x; ++x) {
        glm::vec4 sum(0.0f);
        for (int dy = 0; dy < 2; ++dy)
          for (int dx = 0; dx < 2; ++dx) {
            const int sx = std::min(2 * x + dx, from.x - 1), sy = std::min(2 * y + dy, from.y - 1);
            sum += decodeSrgb8(&src[(size_t(sy) * from.x + sx) * 4]);
          }
        encodeSrgb8(sum / 4.0f, &dst[(size_t(y) * to.x + x) * 4]);
      }
    layer.levelSize.push_back(to);
    layer.levels.push_back(std::move(dst));
  }
}

// Layers of one size share a group. Beyond kMaxGroups sizes, the largest
// kMaxGroups - 1 keep theirs and the rest share one group as large as the
// largest of them in each axis.
void TextureSet::group() {
  std::map<std::pair<int, int>, int> count;
  for (const Layer& l : layers_) ++count[{l.levelSize[0].x, l.levelSize[0].y}];
  std::vector<glm::ivec2> sizes;
  for (const auto& [size, n] : count) sizes.emplace_back(size.first, size.second);
  std::stable_sort(sizes.begin(), sizes.end(),
                   [](glm::ivec2 a, glm::ivec2 b) { return int64_t(a.x) * a.y > int64_t(b.x) * b.y; });
  groupSize_.assign(sizes.begin(), sizes.begin() + std::min<ptrdiff_t>(ptrdiff_t(sizes.size()), kMaxGroups - 1));
  if (sizes.size() > size_t(kMaxGroups - 1)) {
    glm::ivec2 rest(0);
    for (size_t i = kMaxGroups - 1; i < sizes.size(); ++i) rest = glm::max(rest, sizes[i]);
    if (sizes.size() == size_t(kMaxGroups)) rest = sizes.back();
    groupSize_.push_back(rest);
  }
  groupLayers_.assign(groupSize_.size(), 0);
  for (Layer& l : layers_) {
    const auto own = std::find(groupSize_.begin(), groupSize_.end(), l.levelSize[0]);
    l.group = own != groupSize_.end() ? int(own - groupSize_.begin()) : int(groupSize_.size()) - 1;
    l.slice = groupLayers_[size_t(l.group)]++;
  }
}

std::vector<glm::ivec2> TextureSet::slotsOf(const std::vector<int>& layers) const {
  std::vector<glm::ivec2> slots;
  for (int layer : layers)
    slots.push_back(layer < 0 ? glm::ivec2(-1) : glm::ivec2(layers_[size_t(layer)].group, layers_[size_t(layer)].slice));
  return slots;
}

glm::vec4 TextureSet::texel(const Layer& l, int level, int x, int y) const {
  const glm::ivec2 s = l.levelSize[size_t(level)];
  return decodeSrgb8(l.levels[size_t(level)].data() + (size_t(wrap(y, s.y)) * s.x + wrap(x, s.x)) * 4);
}

glm::vec4 TextureSet::bilinear(const Layer& l, int level, glm::vec2 uv) const {
  const glm::ivec2 s = l.levelSize[size_t(level)];
  const float sx = uv.x * s.x - 0.5f, sy = uv.y * s.y - 0.5f;
  const float fx0 = std::floor(sx), fy0 = std::floor(sy);
  const int x0 = int(fx0), y0 = int(fy0);
  const float fx = sx - fx0, fy = sy - fy0;
  return glm::mix(glm::mix(texel(l, level, x0, y0), texel(l, level, x0 + 1, y0), fx),
                  glm::mix(texel(l, level, x0, y0 + 1), texel(l, level, x0 + 1, y0 + 1), fx), fy);
}

glm::vec4 TextureSet::sample(int layer, glm::vec2 uv, float lod) const {
  if (!std::isfinite(uv.x) || !std::isfinite(uv.y)) return glm::vec4(0.0f);
  const Layer& l = layers_[size_t(layer)];
  uv -= glm::floor(uv);  // repeat; keeps float precision for large uv
  const int levels = int(l.levelSize.size());
  lod = std::clamp(std::isfinite(lod) ? lod : 0.0f, 0.0f, float(levels - 1));
  const int l0 = int(std::floor(lod)), l1 = std::min(l0 + 1, levels - 1);
  return glm::mix(bilinear(l, l0, uv), bilinear(l, l1, uv), lod - float(l0));
}

float TextureSet::lodFor(int layer, glm::vec2 duv) const {
  const float texels = glm::length(duv * glm::vec2(size(layer)));
  return texels > 0.0f ? std::log2(texels) : 0.0f;
}

std::vector<gl::Texture> TextureSet::upload() const {
  std::vector<gl::Texture> groups;
  gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  for (size_t g = 0; g < groupSize_.size(); ++g) {
    gl::Texture& tex = groups.emplace_back(GL_TEXTURE_2D_ARRAY);
    const glm::ivec2 size = groupSize_[g];
    // A group's layers share one size, so one chain length.
    const auto first = std::find_if(layers_.begin(), layers_.end(), [&](const Layer& l) { return l.group == int(g); });
    const int levels = int(first->levelSize.size());
    // sRGB texels: GL decodes them to linear before filtering.
    gl::TextureStorage3D(tex.id(), levels, GL_SRGB8_ALPHA8, size.x, size.y, groupLayers_[g]);
    for (const Layer& l : layers_) {
      if (l.group != int(g)) continue;
      for (int level = 0; level < levels; ++level)
        gl::TextureSubImage3D(tex.id(), level, 0, 0, l.slice, l.levelSize[size_t(level)].x, l.levelSize[size_t(level)].y, 1,
                              GL_RGBA, GL_UNSIGNED_BYTE, l.levels[size_t(level)].data());
    }
    tex.filter(GL_LINEAR_MIPMAP_LINEAR, GL_LINEAR);
    tex.wrap(GL_REPEAT);
  }
  gl::checkError("uploading textures");
  return groups;
}

const char* TextureSet::glslSurfaceTexel() {
  // Only with TEXTURE: a function that samples makes the arrays' samplers
  // active, which a program of a scene without textures must not have.
  return R"(
#ifdef TEXTURE
vec4 surfaceTexel(int material, vec2 uv) {
  vec4 texel = materialTexel(material, uv, dFdx(uv), dFdy(uv));
#ifdef MASK
  if (maskedOut(material, texel.a)) discard;
#endif
  return texel;
}
#endif
#ifdef EMISSION_TEXTURE
vec3 surfaceGlow(int material, vec2 uv) { return materialGlow(material, uv, dFdx(uv), dFdy(uv)); }
#endif
)";
}

const std::string& TextureSet::glsl() {
  static const std::string src = [] {
    std::string samplers, grad, lod, size;
    for (int g = 0; g < kMaxGroups; ++g) {
      const std::string name = "uTextureGroup" + std::to_string(g), at = "    case " + std::to_string(g) + ": ";
      samplers += "layout(binding = " + std::to_string(kFirstUnit + unsigned(g)) + ") uniform sampler2DArray " + name + ";\n";
      grad += at + "return textureGrad(" + name + ", p, dx, dy);\n";
      lod += at + "return textureLod(" + name + ", p, lod);\n";
      size += at + "return vec2(textureSize(" + name + ", 0).xy);\n";
    }
    // Each case names its sampler by a constant, as GLSL asks of a
    // non-uniform choice; the gradients come from the caller, computed
    // where control flow is uniform.
    return samplers + "vec4 groupTexelGrad(int g, vec3 p, vec2 dx, vec2 dy) {\n  switch (g) {\n" + grad +
           "  }\n  return vec4(1.0);\n}\nvec4 groupTexelLod(int g, vec3 p, float lod) {\n  switch (g) {\n" + lod +
           "  }\n  return vec4(1.0);\n}\nvec2 groupSize(int g) {\n  switch (g) {\n" + size + R"(  }
  return vec2(1.0);
}
vec4 materialTexel(int material, vec2 uv, vec2 dx, vec2 dy) {
  float layer = uMaterials[material].params.y;
  return layer < 0.0 ? vec4(1.0) : groupTexelGrad(int(uMaterials[material].reflectivity.w), vec3(uv, layer), dx, dy);
}
vec4 materialTexelLod(int material, vec2 uv, float lod) {
  float layer = uMaterials[material].params.y;
  return layer < 0.0 ? vec4(1.0) : groupTexelLod(int(uMaterials[material].reflectivity.w), vec3(uv, layer), lod);
}
vec2 materialTextureSize(int material) { return groupSize(int(uMaterials[material].reflectivity.w)); }
vec3 materialGlow(int material, vec2 uv, vec2 dx, vec2 dy) {
  vec4 g = uMaterials[material].glow;
  vec3 e = uMaterials[material].emission.rgb;
  return hasEmissionTexture(material) ? e * groupTexelGrad(int(g.y), vec3(uv, g.z), dx, dy).rgb : e;
}
vec4 emissionTexelLod(int material, vec2 uv, float lod) {
  vec4 g = uMaterials[material].glow;
  return hasEmissionTexture(material) ? groupTexelLod(int(g.y), vec3(uv, g.z), lod) : vec4(1.0);
}
vec2 emissionTextureSize(int material) { return groupSize(int(uMaterials[material].glow.y)); }
)";
  }();
  return src;
}

}  // namespace mvr::shading
