#include "slicing/gpu/gpu_source_visibility.h"

#include <algorithm>

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

gl::Program compute(const char* name, const char* main) {
  return gl::linkProgram(name, {{GL_COMPUTE_SHADER, gl::glslHeader() + kCommon + main}});
}

}  // namespace

GpuVisibility::GpuVisibility() : rows_(compute("visibility-rows", kRows)), hide_(compute("visibility-hide", kHide)) {}

std::vector<LayerVisibility> GpuVisibility::hide(DeviceLayers& layers, const ShearingCamera& cam, float overlap) {
  const int w = layers.width(), h = layers.height(), count = layers.count();
  if (count == 0) return {};
  std::vector<glm::dvec2> eyes;
  for (int k = 0; k < count; ++k) eyes.push_back(layers.eye(k));
  const std::vector<int> front = nearestLayerOf(eyes);
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
  for (GLuint i = 0; i < 6; ++i) gl::BindBufferBase(GL_SHADER_STORAGE_BUFFER, i, buffers[i]);
  for (const gl::Program* p : {&rows_, &hide_}) {
    gl::setUniform(*p, "uWidth", w);
    gl::setUniform(*p, "uHeight", h);
    gl::setUniform(*p, "uOverlap", overlap);
  }
  gl::UseProgram(rows_.id());
  gl::DispatchCompute(uint32_t((h + 63) / 64), uint32_t(count), 1);
  gl::MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  gl::UseProgram(hide_.id());
  gl::DispatchCompute(uint32_t((w + 63) / 64), uint32_t(h), uint32_t(count));
  gl::MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<uint32_t> out(zeros.size());
  gl::GetNamedBufferSubData(counts.id(), 0, GLsizeiptr(out.size() * sizeof(uint32_t)), out.data());
  gl::checkError("GPU visibility");
  std::vector<LayerVisibility> result(static_cast<size_t>(count));
  for (size_t k = 0; k < result.size(); ++k) result[k] = {long(out[2 * k]), long(out[2 * k + 1])};
  return result;
}

}  // namespace mvr
