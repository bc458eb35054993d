#include "epi/gpu/scene_vectors.h"

#include <algorithm>
#include <string>

#include "mvr/error.h"
#include "mvr/gl/gl_program.h"
#include "shading/texture_vector.h"
#include "shading/view_dependent.h"

namespace mvr {
namespace {

// TextureVectors::lengthFor.
const char* const kLength = R"(
uint lengthFor(float width) {
  float c = isinf(width) || isnan(width) ? 1.0 : ceil(width);
  uint k = uint(clamp(c, 1.0, float(MAX_LENGTH)));
  return k == 1u ? 1u : 1u << uint(findMSB(k - 1u) + 1);
}
float textureLayer(uint word) { return uMaterials[word & 0x7FFFFFFFu].params.y; }
// A slice's chains: its base texture's, then its emission texture's if any.
uint chainsOf(uint word) { return hasEmissionTexture(int(word & 0x7FFFFFFFu)) ? 2u : 1u; }
)";

// The widest p-edge of the pieces drawn, as the CPU's addVector reads it
// from makePst: rows 0 and the last drawn piece's bottom (the edge-on view
// r* where the second piece is culled).
const char* const kSize = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 7) readonly buffer Pieces { uvec2 uPieces[]; };
layout(std430, binding = 8) writeonly buffer Base { uint uBase[]; };  // texel counts, scanned later
layout(std430, binding = 9) writeonly buffer Length { uint uLength[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uSliceCount) return;
  End e0, e1;
  uint word;
  sliceEnds(uFirstSlice + i, e0, e1, word);
  uvec2 piece = uPieces[i];
  uint k0 = piece.x & 0xFFFFu, k1 = piece.x >> 16, flags = piece.y >> 16, k = 0u;
  if ((k0 | k1) != 0u && textureLayer(word) >= 0.0) {
    float n = uViews, bottom = k1 == 0u ? pstPieces(e0, e1, n, false).bottom.x : n;
    k = lengthFor(max(abs(widthAt(e0, e1, 0.0)), abs(widthAt(e0, e1, bottom))));
  }
  uBase[i] = k == 0u ? 0u : chainsOf(word) * (2u * k - 1u);
  uLength[i] = k;
}
)";

// TextureVectors::add's level 0: the surface at screen parameter
// u = (t + 0.5) / K, at the level of the texel's footprint.
const char* const kSample = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 8) readonly buffer Base { uint uBase[]; };
layout(std430, binding = 9) readonly buffer Length { uint uLength[]; };
layout(std430, binding = 10) writeonly buffer Texels { vec4 uTexels[]; };
uniform uint uTexelCount;
uniform int uUv;

vec2 uvAt(End e0, End e1, float u) {
  vec2 a = vec2(endAttribute(e0, uUv), endAttribute(e0, uUv + 1));
  vec2 b = vec2(endAttribute(e1, uUv), endAttribute(e1, uUv + 1));
  return (a + (b - a) * u) / (e0.invW + (e1.invW - e0.invW) * u);
}

void main() {
  uint t = gl_GlobalInvocationID.x;
  if (t >= uTexelCount) return;
  uint lo = 0u, hi = uSliceCount - 1u;  // the last slice whose first texel is at or before t
  while (lo < hi) {
    uint mid = (lo + hi + 1u) >> 1;
    if (uBase[mid] <= t) lo = mid; else hi = mid - 1u;
  }
  uint k = uLength[lo], local = t - uBase[lo], chain = local / (2u * k - 1u);
  local -= chain * (2u * k - 1u);
  if (local >= k) return;  // a MIP level: the levels pass
  End e0, e1;
  uint word;
  sliceEnds(uFirstSlice + lo, e0, e1, word);
  float kf = float(k), u = (float(local) + 0.5) / kf;
  vec2 uv = uvAt(e0, e1, u);
  vec2 duv = uvAt(e0, e1, min(1.0, u + 0.5 / kf)) - uvAt(e0, e1, max(0.0, u - 0.5 / kf));
  int material = int(word & 0x7FFFFFFFu);
  vec2 size = chain == 0u ? materialTextureSize(material) : emissionTextureSize(material);
  float texels = length(duv * size);
  float lod = texels > 0.0 ? log2(texels) : 0.0;
  lod = clamp(isnan(lod) ? 0.0 : lod, 0.0, floor(log2(max(size.x, size.y))));
  bool finite = !any(isnan(uv)) && !any(isinf(uv));
  vec4 texel = chain == 0u ? materialTexelLod(material, uv - floor(uv), lod)
                           : emissionTexelLod(material, uv - floor(uv), lod);
  uTexels[t] = finite ? texel : vec4(0.0);
}
)";

// TextureVectors::addLevels: level l + 1 box-filtered from level l.
const char* const kLevels = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 8) readonly buffer Base { uint uBase[]; };
layout(std430, binding = 9) readonly buffer Length { uint uLength[]; };
layout(std430, binding = 10) buffer Texels { vec4 uTexels[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uSliceCount) return;
  uint k = uLength[i];
  if (k == 0u) return;
  End e0, e1;
  uint word;
  sliceEnds(uFirstSlice + i, e0, e1, word);
  for (uint c = 0u, chains = chainsOf(word); c < chains; ++c)
    for (uint len = k / 2u, from = uBase[i] + c * (2u * k - 1u); len >= 1u; from += 2u * len, len /= 2u)
      for (uint j = 0u; j < len; ++j)
        uTexels[from + 2u * len + j] = 0.5 * (uTexels[from + 2u * j] + uTexels[from + 2u * j + 1u]);
}
)";

const char* const kPull = R"(
layout(std430, binding = 8) readonly buffer VectorBase { uint uVectorBase[]; };
layout(std430, binding = 9) readonly buffer VectorLength { uint uVectorLength[]; };
uvec4 sliceVector(uint slice) {
  return uvec4(uVectorBase[slice], uVectorLength[slice], floatBitsToUint(0.0), floatBitsToUint(1.0));
}
)";

gl::Program compile(const char* name, const std::string& pstLibrary, const char* main) {
  const std::string header = gl::glslHeader({"MAX_LENGTH " + std::to_string(shading::TextureVectors::kMaxLength)});
  return gl::linkProgram(name, {{GL_COMPUTE_SHADER, header + pstLibrary +
                                                        shading::glslMaterials() + shading::TextureSet::glsl() +
                                                        kLength + main}});
}

GLuint groups(size_t items) { return GLuint((items + 63) / 64); }

}  // namespace

const char* SceneVectors::glslPull() { return kPull; }

SceneVectors::SceneVectors(const std::string& pstLibrary, int uvAt, const shading::TextureSet& textures)
    : size_(compile("vector-size", pstLibrary, kSize)),
      sample_(compile("vector-sample", pstLibrary, kSample)),
      levels_(compile("vector-levels", pstLibrary, kLevels)) {
  if (textures.empty()) fail("SceneVectors", "the scene has no textures");
  gl::setUniform(sample_, "uUv", uvAt);
  total_ = gl::makeBuffer<uint32_t>(nullptr, 1);
}

void SceneVectors::setUniforms(const gl::Program& p) const {
  gl::setUniform(p, "uFirstSlice", GLuint(firstSlice_));
  gl::setUniform(p, "uSliceCount", GLuint(sliceCount_));
  gl::setUniform(p, "uViews", float(views_));
}

void SceneVectors::build(uint32_t firstSlice, uint32_t sliceCount, int views,
                         const shading::GpuMaterials& materials) {
  firstSlice_ = firstSlice, sliceCount_ = sliceCount, views_ = views;
  texelCount_ = 0;
  if (sliceCount == 0) return;
  reserveSlices(sliceCount);
  auto run = [&](const gl::Program& p, size_t items) {
    p.use();
    setUniforms(p);
    materials.bind();
    base_.bindStorage(kBase);
    length_.bindStorage(kLength);
    if (texels_.id()) texels_.bindStorage(kTexels);
    gl::dispatch(groups(items), 1, 1);
  };
  run(size_, sliceCount);
  prefixSum_.exclusive(base_.id(), 0, sliceCount, total_.id(), 0);
  uint32_t total = 0;
  total_.read(0, sizeof(total), &total);
  texelCount_ = total;
  if (total == 0) return;
  reserveTexels(total);
  gl::setUniform(sample_, "uTexelCount", GLuint(total));
  run(sample_, total);
  run(levels_, sliceCount);
  gl::MemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
}

void SceneVectors::reserveSlices(uint32_t count) {
  if (count <= sliceCapacity_) return;
  sliceCapacity_ = count + count / 4;
  base_ = gl::makeBuffer<uint32_t>(nullptr, sliceCapacity_);
  length_ = gl::makeBuffer<uint32_t>(nullptr, sliceCapacity_);
}

// Texels are read through a buffer texture and written as a storage
// block: both have GL limits, checked here with the counts they hit.
void SceneVectors::reserveTexels(size_t count) {
  if (count <= texelCapacity_) return;
  GLint texelLimit = 0, blockLimit = 0;
  gl::GetIntegerv(GL_MAX_TEXTURE_BUFFER_SIZE, &texelLimit);
  gl::GetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &blockLimit);
  const size_t limit = std::min(size_t(texelLimit), size_t(unsigned(blockLimit)) / sizeof(glm::vec4));
  if (count > limit)
    fail("SceneVectors", "a batch's " + std::to_string(count) + " texture-vector texels pass the GL's limit of " +
                             std::to_string(limit));
  texelCapacity_ = std::min(limit, count + count / 4);
  texels_ = gl::makeBuffer<glm::vec4>(nullptr, texelCapacity_);
  texelTexture_ = gl::Texture::overBuffer(GL_RGBA32F, texels_.id());
}

void SceneVectors::bind(GLuint vectorUnit) const {
  base_.bindStorage(kBase);
  length_.bindStorage(kLength);
  if (texelTexture_.id()) texelTexture_.bind(vectorUnit);
}

}  // namespace mvr
