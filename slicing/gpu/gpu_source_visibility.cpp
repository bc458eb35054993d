#include "slicing/gpu/gpu_source_visibility.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <string>

#include "mvr/error.h"
#include "mvr/gl/gl_program.h"
#include "slicing/image_slices.h"
#include "slicing/source_visibility.h"

namespace mvr {
namespace {

// Layer k's pixels are k * height * width + j * width + x (DeviceLayers).
// A front layer's row j has two prefix counts of width + 1 entries (empty
// pixels, then cracks: neighbours whose depth step opens more than twice
// the overlap anywhere on the track) and its covered depth range.
const char* const kCommon = R"(
layout(std430, binding = 0) buffer Depth { float uDepth[]; };
layout(std430, binding = 1) readonly buffer Front { int uFront[]; };        // per layer: its source's nearest
layout(std430, binding = 2) readonly buffer Motion { double uMotion[]; };  // per layer: px per unit depth step
layout(std430, binding = 3) buffer Prefix { int uPrefix[]; };
layout(std430, binding = 4) buffer Range { vec2 uRange[]; };  // per layer row: lo, hi
layout(std430, binding = 5) buffer Counts { uint uCounts[]; };  // per layer: covered, kept
uniform int uWidth;
uniform int uHeight;
uniform float uOverlap;

uint pixelIndex(int k, int j, int x) { return (uint(k) * uint(uHeight) + uint(j)) * uint(uWidth) + uint(x); }
uint rowIndex(int k, int j) { return uint(k) * uint(uHeight) + uint(j); }
uint emptyAt(int k, int j) { return rowIndex(k, j) * 2u * uint(uWidth + 1); }
uint cracksAt(int k, int j) { return emptyAt(k, j) + uint(uWidth + 1); }
)";

// hideInvisible's first loop: one invocation per front layer row.
const char* const kRows = R"(
layout(local_size_x = 64) in;
void main() {
  int j = int(gl_GlobalInvocationID.x), k = int(gl_GlobalInvocationID.y);
  if (j >= uHeight || uFront[k] != k) return;
  uint e = emptyAt(k, j), c = cracksAt(k, j), p = pixelIndex(k, j, 0);
  uPrefix[e] = 0;
  uPrefix[c] = 0;
  float lo = 1.0, hi = 0.0;
  for (int x = 0; x < uWidth; ++x) {
    float d = uDepth[p + uint(x)];
    bool crack = x + 1 < uWidth && double(abs(uDepth[p + uint(x + 1)] - d)) * uMotion[k] > 2.0lf * double(uOverlap);
    uPrefix[e + uint(x + 1)] = uPrefix[e + uint(x)] + (d == 0.0 ? 1 : 0);
    uPrefix[c + uint(x + 1)] = uPrefix[c + uint(x)] + (crack ? 1 : 0);
    if (d > 0.0) {
      lo = min(lo, d);
      hi = max(hi, d);
    }
  }
  uRange[rowIndex(k, j)] = vec2(lo, hi);
}
)";

// Its second: one invocation per pixel of a layer behind.
const char* const kHide = R"(
layout(local_size_x = 64) in;
// Entries [a, b] of the prefix count at `at` (PrefixCount::in).
int countIn(uint at, int a, int b) { return b < a ? 0 : uPrefix[at + uint(b + 1)] - uPrefix[at + uint(a)]; }
void main() {
  int x = int(gl_GlobalInvocationID.x), j = int(gl_GlobalInvocationID.y), k = int(gl_GlobalInvocationID.z);
  int f = uFront[k];
  if (x >= uWidth || f == k) return;
  uint p = pixelIndex(k, j, x);
  float d = uDepth[p];
  if (d == 0.0) return;
  atomicAdd(uCounts[2 * k], 1u);
  vec2 range = uRange[rowIndex(f, j)];
  int r = int(ceil(uMotion[f] * double(max(range.y - d, d - range.x)))) + 1;
  bool covered = x - r >= 0 && x + r < uWidth && countIn(emptyAt(f, j), x - r, x + r) == 0 &&
                 countIn(cracksAt(f, j), x - r, x + r - 1) == 0;
  if (covered) uDepth[p] = 0.0;
  else atomicAdd(uCounts[2 * k + 1], 1u);
}
)";

// countHoles: the layers a check uses splatted into the view at uEyeXView
// (uCovered: the nearest splatted depth's bits per pixel; positive floats
// order as their bits), then each scanline's gaps tested.
const char* const kHoles = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Depth { float uDepth[]; };
layout(std430, binding = 1) readonly buffer Use { ivec2 uUse[]; };  // per layer: used, its source's nearest
layout(std430, binding = 2) readonly buffer Eyes { double uEyeX[]; };
layout(std430, binding = 3) buffer Covered { uint uCovered[]; };
layout(std430, binding = 4) buffer Result { uint uResult[]; };  // lo and hi depth bits, holes
uniform int uWidth;
uniform int uHeight;
uniform double uNear, uFar, uDistance, uPerPlane;  // uPerPlane: W / Wp
uniform double uEyeXView, uFarthest, uPixelsPerDepth;
uniform float uOverlap;

uint pixelIndex(int k, int j, int x) { return (uint(k) * uint(uHeight) + uint(j)) * uint(uWidth) + uint(x); }

// TrackParallax::shift, operation for operation.
double shift(float depth, double from, double to) {
  double w = uNear * uFar / (double(depth) * (uFar - uNear) + uNear);
  double z = uDistance - w;
  return (to - from) * (-uPerPlane * z / (uDistance - z));
}

#if defined(RANGE) || defined(SPLAT)
void main() {
  int x = int(gl_GlobalInvocationID.x), j = int(gl_GlobalInvocationID.y), k = int(gl_GlobalInvocationID.z);
  if (x >= uWidth || uUse[k].x == 0) return;
  float d = uDepth[pixelIndex(k, j, x)];
  if (d == 0.0) return;
#ifdef RANGE
  atomicMin(uResult[0], floatBitsToUint(d));
  atomicMax(uResult[1], floatBitsToUint(d));
#else
  double at = double(x) + shift(d, uEyeX[k], uEyeXView);
  // Pixel centres c + 0.5 in [at - overlap, at + 1 + overlap).
  int first = max(0, int(ceil(at - double(uOverlap) - 0.5lf)));
  int last = min(uWidth, int(ceil(at + 1.0lf + double(uOverlap) - 0.5lf)));
  for (int c = first; c < last; ++c) atomicMax(uCovered[uint(j) * uint(uWidth) + uint(c)], floatBitsToUint(d));
#endif
}
#else
// isHole: every nearest layer used is covered where either side's depth
// puts pixel x.
bool isHole(int j, int x, float side0, float side1) {
  for (int l = 0; l < uUse.length(); ++l) {
    if (uUse[l].x == 0 || uUse[l].y == 0) continue;
    for (int k = 0; k < 2; ++k) {
      double at = double(x) + 0.5lf + shift(k == 0 ? side0 : side1, uEyeXView, uEyeX[l]);
      if (at < 0.0lf || at >= double(uWidth) || uDepth[pixelIndex(l, j, int(at))] == 0.0) return false;
    }
  }
  return true;
}

void main() {
  int j = int(gl_GlobalInvocationID.x);
  if (j >= uHeight) return;
  float lo = uintBitsToFloat(uResult[0]), hi = uintBitsToFloat(uResult[1]);
  // The widest gap the depth range can open between a source and the view.
  int widest = int(ceil(uFarthest * uPixelsPerDepth * double(max(0.0, hi - lo)))) + 1;
  uint holes = 0u;
  uint row = uint(j) * uint(uWidth);
  for (int x = 0, lastCovered = -1; x < uWidth; ++x) {
    float c = uintBitsToFloat(uCovered[row + uint(x)]);
    if (c == 0.0) continue;
    int gap = x - lastCovered - 1;
    if (lastCovered >= 0 && gap > 0 && gap <= widest) {
      float side0 = uintBitsToFloat(uCovered[row + uint(lastCovered)]);
      for (int g = lastCovered + 1; g < x; ++g) holes += isHole(j, g, side0, c) ? 1u : 0u;
    }
    lastCovered = x;
  }
  atomicAdd(uResult[2], holes);
}
#endif
)";

gl::Program compute(const char* name, const char* main) {
  return gl::linkProgram(name, {{GL_COMPUTE_SHADER, gl::glslHeader() + kCommon + main}});
}

gl::Program holesPass(const char* name, const char* define) {
  const std::string header = define ? gl::glslHeader({define}) : gl::glslHeader();
  return gl::linkProgram(name, {{GL_COMPUTE_SHADER, header + kHoles}});
}

void setDouble(const gl::Program& p, const char* name, double v) {
  gl::setUniform(p, name, v);
}

}  // namespace

GpuVisibility::GpuVisibility()
    : rows_(compute("visibility-rows", kRows)), hide_(compute("visibility-hide", kHide)),
      range_(holesPass("holes-range", "RANGE")), splat_(holesPass("holes-splat", "SPLAT")),
      gaps_(holesPass("holes-gaps", nullptr)) {}

std::vector<LayerVisibility> GpuVisibility::hide(DeviceLayers& layers, const ShearingCamera& cam, float overlap,
                                                 int from) {
  const int w = layers.width(), h = layers.height(), count = layers.count();
  if (count == 0) return {};
  std::vector<glm::dvec2> eyes;
  for (int k = 0; k < count; ++k) eyes.push_back(layers.eye(k));
  std::vector<int> front = nearestLayerOf(eyes);
  for (int k = 0; k < std::min(from, count); ++k) front[size_t(k)] = k;  // not tested: as a nearest
  // hideInvisible's k: pixels of relative motion per unit of depth step at
  // the track's farthest view from the source.
  const TrackParallax parallax(cam);
  std::vector<double> motion(static_cast<size_t>(count));
  for (int k = 0; k < count; ++k) motion[size_t(k)] = parallax.reach(eyes[size_t(k)].x) * parallax.pixelsPerDepth();
  const gl::Buffer fronts = gl::makeBuffer(front.data(), front.size());
  const gl::Buffer motions = gl::makeBuffer(motion.data(), motion.size());
  const size_t prefix = size_t(count) * h * 2 * (w + 1);
  if (prefix > prefixSize_) {
    prefix_ = gl::makeBuffer<int32_t>(nullptr, prefix);
    prefixSize_ = prefix;
  }
  const gl::Buffer range = gl::makeBuffer<glm::vec2>(nullptr, size_t(count) * h);
  const std::vector<uint32_t> zeros(2 * size_t(count), 0);
  const gl::Buffer counts = gl::makeBuffer(zeros.data(), zeros.size(), GL_DYNAMIC_STORAGE_BIT);
  const GLuint buffers[] = {layers.depthBuffer(), fronts.id(), motions.id(), prefix_.id(), range.id(), counts.id()};
  for (GLuint i = 0; i < 6; ++i) gl::bindStorage(i, buffers[i]);
  for (const gl::Program* p : {&rows_, &hide_}) {
    gl::setUniform(*p, "uWidth", w);
    gl::setUniform(*p, "uHeight", h);
    gl::setUniform(*p, "uOverlap", overlap);
  }
  rows_.use();
  gl::dispatch(uint32_t((h + 63) / 64), uint32_t(count), 1);
  hide_.use();
  gl::dispatch(uint32_t((w + 63) / 64), uint32_t(h), uint32_t(count), GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<uint32_t> out(zeros.size());
  counts.read(0, GLsizeiptr(out.size() * sizeof(uint32_t)), out.data());
  gl::checkError("GPU visibility");
  std::vector<LayerVisibility> result(static_cast<size_t>(count));
  for (size_t k = 0; k < result.size(); ++k) result[k] = {long(out[2 * k]), long(out[2 * k + 1])};
  return result;
}

long GpuVisibility::holes(const DeviceLayers& layers, const std::vector<uint8_t>& use, const ShearingCamera& cam,
                          double eyeX, float overlap) {
  const int w = layers.width(), h = layers.height(), count = layers.count();
  if (int(use.size()) != count) fail("GPU hole count", "a use flag per layer");
  if (count == 0) return 0;
  std::vector<glm::dvec2> eyes;
  for (int k = 0; k < count; ++k) eyes.push_back(layers.eye(k));
  const std::vector<int> front = nearestLayerOf(eyes);
  std::vector<glm::ivec2> roles(static_cast<size_t>(count));
  std::vector<double> eyeXs(static_cast<size_t>(count));
  double farthest = 0.0;
  for (size_t k = 0; k < roles.size(); ++k) {
    roles[k] = {use[k] ? 1 : 0, front[k] == int(k) ? 1 : 0};
    eyeXs[k] = eyes[k].x;
    if (use[k]) farthest = std::max(farthest, std::abs(eyeX - eyes[k].x));
  }
  const gl::Buffer roleBuffer = gl::makeBuffer(roles.data(), roles.size());
  const gl::Buffer eyeBuffer = gl::makeBuffer(eyeXs.data(), eyeXs.size());
  const size_t pixels = size_t(w) * h;
  if (pixels > coveredSize_) {
    covered_ = gl::makeBuffer<uint32_t>(nullptr, pixels);
    coveredSize_ = pixels;
  }
  covered_.fill(pixels);
  // countHoles starts its range at lo = 1, hi = 0.
  const uint32_t start[3] = {std::bit_cast<uint32_t>(1.0f), 0u, 0u};
  const gl::Buffer result = gl::makeBuffer(start, 3, GL_DYNAMIC_STORAGE_BIT);
  const GLuint buffers[] = {layers.depthBuffer(), roleBuffer.id(), eyeBuffer.id(), covered_.id(), result.id()};
  for (GLuint i = 0; i < 5; ++i) gl::bindStorage(i, buffers[i]);
  const CameraSpec& s = cam.spec();
  const TrackParallax parallax(cam);
  for (const gl::Program* p : {&range_, &splat_, &gaps_}) {
    gl::setUniform(*p, "uWidth", w);
    gl::setUniform(*p, "uHeight", h);
    gl::setUniform(*p, "uOverlap", overlap);
    setDouble(*p, "uNear", s.nearDistance);
    setDouble(*p, "uFar", s.farDistance);
    setDouble(*p, "uDistance", s.distance);
    setDouble(*p, "uPerPlane", cam.width() / cam.planeWidth());
    setDouble(*p, "uEyeXView", eyeX);
    setDouble(*p, "uFarthest", farthest);
    setDouble(*p, "uPixelsPerDepth", parallax.pixelsPerDepth());
  }
  for (const gl::Program* p : {&range_, &splat_}) {
    p->use();
    gl::dispatch(uint32_t((w + 63) / 64), uint32_t(h), uint32_t(count));
  }
  gaps_.use();
  gl::dispatch(uint32_t((h + 63) / 64), 1, 1, GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  uint32_t out[3] = {0, 0, 0};
  result.read(0, sizeof out, out);
  gl::checkError("GPU hole count");
  return long(out[2]);
}

}  // namespace mvr
