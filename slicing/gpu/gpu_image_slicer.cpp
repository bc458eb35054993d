#include "slicing/gpu/gpu_image_slicer.h"

#include <algorithm>
#include <bit>
#include <limits>
#include <string>
#include <vector>

#include "mvr/error.h"
#include "mvr/gl/gl_program.h"
#include "shading/texture_vector.h"

namespace mvr {
namespace {

constexpr int kMaxLevel = std::countr_zero(unsigned(shading::TextureVectors::kMaxLength));

// Layer k's pixels are k * height * width + j * width + x; the start flags
// run in slice-table order, (j * layers + k) * width + x.
const char* const kCommon = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Depth { float uDepth[]; };
layout(std430, binding = 1) readonly buffer Color { vec4 uColor[]; };
layout(std430, binding = 2) buffer Mips { vec2 uMips[]; };  // per layer scanline: levels 1.. packed
layout(std430, binding = 3) buffer Flags { uint uFlags[]; };
// Per layer: x shift per unit Z/w, coalescing's depth tolerance, the depth
// step between neighbours of one surface, the front layer of the nearest
// other source (-1: none; LayerSlicer::meetOtherOutline).
layout(std430, binding = 4) readonly buffer Layers { dvec4 uLayers[]; };
layout(std430, binding = 13) readonly buffer Keep { int uKeep[]; };  // per layer: 1 if sliced
layout(std430, binding = 14) readonly buffer Rank { int uRank[]; };  // per layer: its place in the table's order
uniform int uWidth;
uniform int uHeight;
uniform int uLayerCount;
uniform int uLevels;  // of the depth mip, level 0 the pixels; 1: no coalescing

const float kEmpty = 3.0e38;  // an empty pixel's block spans (-kEmpty, kEmpty)

uint pixelIndex(int k, int j, int x) { return (uint(k) * uint(uHeight) + uint(j)) * uint(uWidth) + uint(x); }
uint flagIndex(int k, int j, int x) { return (uint(j) * uint(uLayerCount) + uint(uRank[k])) * uint(uWidth) + uint(x); }
uint mipIndex(int k, int j, int l, int i) {
  int start = 0;
  for (int m = 1; m < l; ++m) start += uWidth >> m;
  return pixelIndex(k, j, 0) + uint(start + i);
}
// Min and max depth of block i of level l.
vec2 depthRange(int k, int j, int l, int i) {
  if (l > 0) return uMips[mipIndex(k, j, l, i)];
  float d = uDepth[pixelIndex(k, j, i)];
  return d == 0.0 ? vec2(-kEmpty, kEmpty) : vec2(d);
}
// The level of the run pixel x starts, or -1: the largest whole, covered
// block holding x whose depths agree, if it starts at x.
int runLevel(int k, int j, int x) {
  if (uDepth[pixelIndex(k, j, x)] == 0.0) return -1;
  float tolerance = float(uLayers[k].y);
  int level = 0;
  for (int l = 1; l < uLevels; ++l) {
    int i = x >> l;
    if (((i + 1) << l) > uWidth) break;
    vec2 r = uMips[mipIndex(k, j, l, i)];
    if (r.x <= -kEmpty || !(r.y - r.x <= tolerance)) break;
    level = l;
  }
  return ((x >> level) << level) == x ? level : -1;
}
)";

const char* const kMip = R"(
uniform int uLevel;
void main() {
  int i = int(gl_GlobalInvocationID.x), j = int(gl_GlobalInvocationID.y), k = int(gl_GlobalInvocationID.z);
  if (i >= (uWidth >> uLevel)) return;
  vec2 a = depthRange(k, j, uLevel - 1, 2 * i), b = depthRange(k, j, uLevel - 1, 2 * i + 1);
  uMips[mipIndex(k, j, uLevel, i)] = vec2(min(a.x, b.x), max(a.y, b.y));
}
)";

// Start flags, and the covered pixels counted per work group first.
const char* const kFlag = R"(
layout(std430, binding = 5) buffer Covered { uint uCovered; };
shared uint sCovered;
void main() {
  if (gl_LocalInvocationIndex == 0u) sCovered = 0u;
  barrier();
  int x = int(gl_GlobalInvocationID.x), j = int(gl_GlobalInvocationID.y), k = int(gl_GlobalInvocationID.z);
  if (x < uWidth) {
    bool kept = uKeep[k] != 0;
    uFlags[flagIndex(k, j, x)] = kept && runLevel(k, j, x) >= 0 ? 1u : 0u;
    if (kept && uDepth[pixelIndex(k, j, x)] != 0.0) atomicAdd(sCovered, 1u);
  }
  barrier();
  if (gl_LocalInvocationIndex == 0u && sCovered > 0u) atomicAdd(uCovered, sCovered);
}
)";

// A run's slice (a segment), endpoint records (GpuVertices' layout, no
// extras), "triangle" and vector, as LayerSlicer::addRun writes them.
const char* const kFill = R"(
layout(std430, binding = 6) writeonly buffer Slices { uvec4 uSlices[]; };
layout(std430, binding = 7) writeonly buffer Records { float uRecords[]; };
layout(std430, binding = 8) writeonly buffer Triangles { uvec4 uTriangles[]; };
layout(std430, binding = 9) writeonly buffer Vectors { uvec4 uVectors[]; };
layout(std430, binding = 10) buffer Texels { vec4 uTexels[]; };
uniform float uOverlap;
uniform dvec2 uZOverW;          // Z / w = x d + y at window depth d
uniform dvec2 uInvW;            // 1 / w = x d + y
uniform double uStepPerZOverW;  // x step per view per unit of Z / w
uniform bool uOwnTexels;        // vectors with MIP chains in Texels, else the colour buffer
layout(std430, binding = 11) readonly buffer Outline { vec4 uOutline[]; };  // PixelOutline per pixel
// Per layer: its source's nearest layer where that has an outline, else -1.
layout(std430, binding = 12) readonly buffer OutlineOf { int uOutlineOf[]; };

// In double, rounded once to float, as the CPU's ExtremeTransform: the two
// back ends then agree to the last bit almost everywhere, and exact mode's
// depth test settles overlapping slices alike.
void writeEnd(uint vertex, float x, float d, double shift, vec3 c) {
  double zOverW = uZOverW.x * double(d) + uZOverW.y;
  float invW = float(uInvW.x * double(d) + uInvW.y);
  uint at = vertex * 10u;
  uRecords[at] = float(double(x) + shift * zOverW);
  uRecords[at + 1u] = float(uStepPerZOverW * zOverW);
  uRecords[at + 2u] = d;
  uRecords[at + 3u] = invW;
  // Front and back colour alike; not one chained assignment, which reads
  // the writeonly buffer back (NVIDIA refuses to link it, llvmpipe allows it).
  for (uint c3 = 0u; c3 < 3u; ++c3) {
    float value = c[c3] * invW;
    uRecords[at + 4u + c3] = value;
    uRecords[at + 7u + c3] = value;
  }
}

// As LayerSlicer: pixel `to` continues the surface of pixel `from`; the
// overlap toward it (beyond the image's edge only: a joined side meets its
// neighbour's slice); a lone pixel's slope between two neighbours of its
// surface.
bool joined(int k, int j, int from, int to) {
  if (to < 0 || to >= uWidth) return false;
  float b = uDepth[pixelIndex(k, j, to)];
  return b != 0.0 && abs(uDepth[pixelIndex(k, j, from)] - b) <= float(uLayers[k].z);
}
float widening(int to) { return to < 0 || to >= uWidth ? uOverlap : 0.0; }
// As LayerSlicer::meetOtherOutline: the ends slide along their rays until
// the slice stops at the other source's outline in that source's view.
bool theirs(int m, int j, int i) { return i >= 0 && i < uWidth && uDepth[pixelIndex(m, j, i)] != 0.0; }
void meetOtherOutline(int k, int m, int j, double xE[2], inout float dE[2]) {
  double delta = uLayers[k].x - uLayers[m].x;
  if (delta == 0.0) return;
  double at[2] = double[2](xE[0] + delta * (uZOverW.x * double(dE[0]) + uZOverW.y),
                           xE[1] + delta * (uZOverW.x * double(dE[1]) + uZOverW.y));
  double l = at[0], r = at[1];
  if (!(r > l)) return;
  int first = int(ceil(l - 0.5)), last = int(ceil(r - 0.5)) - 1;
  int a = first, b = last;
  while (a <= b && !theirs(m, j, a)) ++a;
  while (b >= a && !theirs(m, j, b)) --b;
  double target[2] = double[2](a > first ? double(a) : l, b < last ? double(b + 1) : r);
  if (a > b) {
    if (theirs(m, j, first - 1)) { target[0] = l; target[1] = max(l, double(first)); }
    else if (theirs(m, j, last + 1)) { target[0] = min(r, double(last + 1)); target[1] = r; }
    else { target[0] = floor(0.5 * (l + r) + 0.5); target[1] = target[0]; }
  }
  for (int e = 0; e < 2; ++e) {
    if (target[e] == at[e] || abs(target[e] - at[e]) > 1.0) continue;
    double moved = ((target[e] - xE[e]) / delta - uZOverW.y) / uZOverW.x;
    if (moved > 0.0 && moved <= 1.0) dE[e] = float(moved);
  }
}

float surfaceSlope(int k, int j, int x) {
  if (joined(k, j, x, x - 1) && joined(k, j, x, x + 1))
    return 0.5 * (uDepth[pixelIndex(k, j, x + 1)] - uDepth[pixelIndex(k, j, x - 1)]);
  if (x < 1 || x + 1 >= uWidth) return 0.0;
  float before = uDepth[pixelIndex(k, j, x - 1)], at = uDepth[pixelIndex(k, j, x)],
        after = uDepth[pixelIndex(k, j, x + 1)];
  if (before == 0.0 || after == 0.0) return 0.0;
  float a = at - before, b = after - at;
  if (!(a * b > 0.0)) return 0.0;
  return abs(a) < abs(b) ? a : b;
}

// As LayerSlicer::outlineEnd: pixel i's end toward an empty pixel at
// i + dir of its source's nearest layer on that layer's finer outline,
// where it has one; a layer behind it kBehindOutline of the way back to
// its own depth.
const float kBehindOutline = 0.75;
const double kBehindInset = 0.25;
bool outlineEnd(int k, int j, int i, int dir, inout double end, inout float d) {
  int m = uOutlineOf[k], next = i + dir;
  if (m < 0 || next < 0 || next >= uWidth || uDepth[pixelIndex(m, j, next)] != 0.0) return false;
  vec4 o = uOutline[pixelIndex(m, j, i)];
  if (o.z < 0.0) return false;  // no sample covered (left may be below 0)
  float at = dir < 0 ? o.y : o.w;
  if (m != k) {
    at += kBehindOutline * (d - at);
    if (abs(at - d) > 2.0 * float(uLayers[k].z)) return false;  // LayerSlicer::outlineEnd: another object
  }
  end = double(i) + double(dir < 0 ? o.x : o.z);
  d = at;
  return true;
}

void main() {
  int x = int(gl_GlobalInvocationID.x), j = int(gl_GlobalInvocationID.y), k = int(gl_GlobalInvocationID.z);
  if (x >= uWidth) return;
  int level = uKeep[k] != 0 ? runLevel(k, j, x) : -1;
  if (level < 0) return;
  uint slot = uFlags[flagIndex(k, j, x)], p = pixelIndex(k, j, x);
  int n = 1 << level;
  float d0 = uDepth[p], slope = n > 1 ? (uDepth[p + uint(n - 1)] - d0) / float(n - 1) : surfaceSlope(k, j, x);
  float oL = widening(x - 1), oR = widening(x + n);
  double shift = uLayers[k].x;
  vec3 c = uColor[p].rgb;
  double xE[2] = double[2](double(float(x) - oL), double(float(x + n) + oR));
  float dE[2] = float[2](d0 + (-oL - 0.5) * slope, d0 + (float(n) + oR - 0.5) * slope);
  if (joined(k, j, x, x - 1)) dE[0] = 0.5 * (uDepth[pixelIndex(k, j, x - 1)] + d0);
  if (joined(k, j, x + n - 1, x + n)) dE[1] = 0.5 * (uDepth[p + uint(n - 1)] + uDepth[pixelIndex(k, j, x + n)]);
  bool onOutline[2] = bool[2](outlineEnd(k, j, x, -1, xE[0], dE[0]), outlineEnd(k, j, x + n - 1, 1, xE[1], dE[1]));
  bool moved[2] = bool[2](onOutline[0], onOutline[1]);
  int front = uOutlineOf[k], other = int(uLayers[k].w);
  if (front >= 0 && front != k) {  // LayerSlicer::insetBehind
    if (onOutline[0]) {
      xE[0] = max(xE[0], double(x) + kBehindInset);
    } else if (x > 0 && uDepth[pixelIndex(k, j, x - 1)] != 0.0 && !joined(k, j, x, x - 1)) {
      xE[0] = double(x) + kBehindInset;
      dE[0] += float(kBehindInset) * slope;
      moved[0] = true;
    }
    if (onOutline[1]) {
      xE[1] = min(xE[1], double(x + n) - kBehindInset);
    } else if (x + n < uWidth && uDepth[pixelIndex(k, j, x + n)] != 0.0 && !joined(k, j, x + n - 1, x + n)) {
      xE[1] = double(x + n) - kBehindInset;
      dE[1] -= float(kBehindInset) * slope;
      moved[1] = true;
    }
  }
  if (other >= 0 && front < 0) meetOtherOutline(k, other, j, xE, dE);
  writeEnd(2u * slot, float(xE[0]), dE[0], shift, c);
  writeEnd(2u * slot + 1u, float(xE[1]), dE[1], shift, c);
  uSlices[slot] = uvec4(slot, 0u, 0u, 256u);  // a segment
  uTriangles[slot] = uvec4(2u * slot, 2u * slot + 1u, 2u * slot + 1u, 0u);
  uint base = uOwnTexels ? 2u * p : p;
  float u0 = moved[0] ? float(xE[0] - double(x)) / float(n) : -oL / float(n);
  float u1 = moved[1] ? float(xE[1] - double(x)) / float(n) : 1.0 + oR / float(n);
  uVectors[slot] = uvec4(base, uint(n), floatBitsToUint(u0), floatBitsToUint(u1));
  if (!uOwnTexels) return;
  // Level 0 and its box-filtered MIP chain (TextureVectors::addTexels).
  for (int i = 0; i < n; ++i) uTexels[base + uint(i)] = vec4(uColor[p + uint(i)].rgb, 1.0);
  uint from = base, to = base + uint(n);
  for (uint len = uint(n) / 2u; len >= 1u; len /= 2u) {
    for (uint i = 0u; i < len; ++i) uTexels[to + i] = 0.5 * (uTexels[from + 2u * i] + uTexels[from + 2u * i + 1u]);
    from = to;
    to += len;
  }
}
)";

gl::Program compute(const char* name, const char* main) {
  return gl::linkProgram(name, {{GL_COMPUTE_SHADER, gl::glslHeader() + kCommon + main}});
}

uint32_t groups(size_t n) { return uint32_t((n + 63) / 64); }

}  // namespace

GpuImageSlicer::GpuImageSlicer()
    : mip_(compute("image-slice-mip", kMip)), flag_(compute("image-slice-flag", kFlag)),
      fill_(compute("image-slice-fill", kFill)) {}

GpuImageSlices GpuImageSlicer::build(const DeviceLayers& layers, const ShearingCamera& cam,
                                     const ImageSliceOptions& options, const std::vector<uint8_t>& keep,
                                     const std::vector<int>& order) {
  if (options.scene && options.splits > 0)
    fail("GpuImageSlicer", "split highlight tracks are built on the CPU");
  const int w = cam.width(), h = cam.height(), count = layers.count();
  if (layers.width() != w || layers.height() != h)
    fail("GpuImageSlicer", "source layers must be of the output size");
  const bool coalesce = options.coalesce > 0.0f;
  int levels = 1;
  while (coalesce && levels <= kMaxLevel && (w >> levels) > 0) ++levels;

  // Per layer: pixels per unit of Z / w from its eye to view 0, and the
  // depth range a run may span (coalesceDepthRange; never infinite, so
  // that a block with an empty pixel never passes).
  const double perPlane = w / cam.planeWidth(), left = cam.viewX(0);
  std::vector<glm::dvec4> perLayer(std::max(count, 1));
  std::vector<glm::dvec2> eyes;
  for (int k = 0; k < count; ++k) eyes.push_back(layers.eye(k));
  // Outlines to meet: of the sources this slicing keeps (the store may
  // hold others: hierarchical acquisition's, nearer to some of its layers).
  if (!keep.empty() && int(keep.size()) != count) fail("GpuImageSlicer", "a keep flag per layer");
  const std::vector<int> other = nearestOtherSource(eyes, keep);
  for (int k = 0; k < count; ++k) {
    const double x = layers.eye(k).x;
    const float tolerance = coalesce ? std::min(coalesceDepthRange(cam, x, options.coalesce),
                                                std::numeric_limits<float>::max())
                                     : -1.0f;
    const float join = std::min(coalesceDepthRange(cam, x, 2.0f * options.overlap), std::numeric_limits<float>::max());
    perLayer[k] = glm::dvec4((x - left) * perPlane, tolerance, join, options.meetSilhouettes ? double(other[k]) : -1.0);
  }
  const gl::Buffer layerInfo = gl::makeBuffer(perLayer.data(), perLayer.size());
  const std::vector<int> front = nearestLayerOf(eyes);
  std::vector<int32_t> outlineOf(std::max(count, 1), -1);
  for (int k = 0; k < count; ++k) outlineOf[size_t(k)] = layers.outlined(front[k]) ? front[k] : -1;
  const gl::Buffer outlinedInfo = gl::makeBuffer(outlineOf.data(), outlineOf.size());
  std::vector<int32_t> kept(std::max(count, 1), 1);
  for (size_t k = 0; k < keep.size(); ++k) kept[k] = keep[k] ? 1 : 0;
  const gl::Buffer keepInfo = gl::makeBuffer(kept.data(), kept.size());
  std::vector<int32_t> rank(std::max(count, 1), -1);
  for (int k = 0; k < count; ++k) rank[size_t(order.empty() ? k : order[size_t(k)])] = k;
  if (!order.empty() && (int(order.size()) != count || std::count(rank.begin(), rank.end(), -1) > (count == 0 ? 1 : 0)))
    fail("GpuImageSlicer", "the order must name every layer once");
  const gl::Buffer rankInfo = gl::makeBuffer(rank.data(), rank.size());
  const size_t pixels = layers.pixelsPerLayer() * size_t(count);
  if (pixels > flagsSize_) {
    flagsSize_ = pixels;
    flags_ = gl::makeBuffer<uint32_t>(nullptr, pixels);
  }
  if (levels > 1 && pixels > mipsSize_) {
    mipsSize_ = pixels;
    mips_ = gl::makeBuffer<glm::vec2>(nullptr, pixels);
  }
  const uint32_t zero = 0;
  const gl::Buffer covered = gl::makeBuffer(&zero, 1, GL_DYNAMIC_STORAGE_BIT);
  gl::Buffer offsets = gl::makeBuffer<uint32_t>(nullptr, size_t(h) + 1);

  auto use = [&](const gl::Program& p) {
    p.use();
    gl::setUniform(p, "uWidth", w);
    gl::setUniform(p, "uHeight", h);
    gl::setUniform(p, "uLayerCount", count);
    gl::setUniform(p, "uLevels", levels);
    gl::bindStorage(0, layers.depthBuffer());
    gl::bindStorage(1, layers.colorBuffer());
    gl::bindStorage(2, levels > 1 ? mips_.id() : flags_.id());
    flags_.bindStorage(3);
    layerInfo.bindStorage(4);
    keepInfo.bindStorage(13);
    rankInfo.bindStorage(14);
  };
  auto overPixels = [&](int width) {
    gl::dispatch(groups(size_t(width)), uint32_t(h), uint32_t(count));
  };
  uint32_t coveredPixels = 0;
  if (count > 0) {
    use(mip_);
    for (int l = 1; l < levels; ++l) {
      gl::setUniform(mip_, "uLevel", l);
      overPixels(w >> l);
    }
    use(flag_);
    covered.bindStorage(5);
    overPixels(w);
  }
  // offsets[j]: the slot of scanline j's first run (flags run in
  // (scanline, layer, x) order); offsets[height]: the run count.
  prefixSum_.exclusiveRows(flags_.id(), uint32_t(h), uint32_t(count * w), offsets.id());
  // The one readback: the offsets (for the buffers' sizes and the
  // rasterizer's batches) and the covered pixel count.
  std::vector<uint32_t> hostOffsets(size_t(h) + 1);
  offsets.read(0, GLsizeiptr(hostOffsets.size() * sizeof(uint32_t)), hostOffsets.data());
  covered.read(0, sizeof(uint32_t), &coveredPixels);

  const size_t slices = hostOffsets.back();
  GpuVertices v;
  v.vertexCount = 2 * slices;
  v.triangleCount = slices;
  v.records = gl::makeBuffer<float>(nullptr, 2 * slices * size_t(GpuVertices::kRecordHead));
  v.triangles = gl::makeBuffer<glm::uvec4>(nullptr, slices);
  v.vectors = gl::makeBuffer<glm::uvec4>(nullptr, slices);
  if (levels > 1) {
    v.ownedTexels = gl::makeBuffer<glm::vec4>(nullptr, 2 * pixels);
    v.texelBuffer = v.ownedTexels.id();
    v.texelCount = 2 * pixels;
  } else {
    v.texelBuffer = layers.colorBuffer();
    v.texelCount = pixels;
  }
  gl::Buffer table = gl::makeBuffer<Slice>(nullptr, slices);
  if (slices > 0) {
    use(fill_);
    gl::setUniform(fill_, "uOverlap", options.overlap);
    const CameraSpec& s = cam.spec();
    const double n = s.nearDistance, f = s.farDistance, D = s.distance;
    gl::setUniform(fill_, "uZOverW", glm::dvec2(D * (f - n) / (n * f), D / f - 1.0));
    gl::setUniform(fill_, "uInvW", glm::dvec2((f - n) / (n * f), 1.0 / f));
    const int views = cam.views();
    gl::setUniform(fill_, "uStepPerZOverW", double(views > 1 ? (left - cam.viewX(views - 1)) * perPlane / (views - 1) : 0.0));
    gl::setUniform(fill_, "uOwnTexels", levels > 1 ? 1 : 0);
    table.bindStorage(6);
    v.records.bindStorage(7);
    v.triangles.bindStorage(8);
    v.vectors.bindStorage(9);
    gl::bindStorage(10, v.texelBuffer);
    gl::bindStorage(11, layers.outlineBuffer());
    outlinedInfo.bindStorage(12);
    gl::dispatch(groups(size_t(w)), uint32_t(h), uint32_t(count), GL_SHADER_STORAGE_BARRIER_BIT | GL_TEXTURE_FETCH_BARRIER_BIT);
  }
  gl::checkError("GPU image slicing");
  return {std::move(v), GpuSliceTable::adopt(std::move(table), std::move(offsets), std::move(hostOffsets)),
          coveredPixels};
}

}  // namespace mvr
