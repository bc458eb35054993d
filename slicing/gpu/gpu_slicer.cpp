#include "slicing/gpu/gpu_slicer.h"

#include <algorithm>
#include <string>
#include <vector>

#include "mvr/error.h"
#include "mvr/gl/gl_program.h"

namespace mvr {
namespace {

// The CPU slicer's arithmetic (slicing/slice_table.cpp), term for term.
const char* const kCommon = R"(
layout(std430, binding = 0) readonly buffer Ys { float uY[]; };
layout(std430, binding = 1) readonly buffer Triangles { uvec4 uTriangles[]; };
layout(std430, binding = 2) buffer Cells { uint uCells[]; };  // scanline-major: cell j * blocks + b
uniform uint uTriangleCount;
uniform uint uBlocks;
uniform uint uPerBlock;
uniform int uFirst, uLast;  // the scanlines sliced

// Scanlines [first, last) whose centres j + 0.5 lie in [ymin, ymax).
ivec2 scanlineRange(float y0, float y1, float y2) {
  float lo = min(y0, min(y1, y2)), hi = max(y0, max(y1, y2));
  int first = max(uFirst, int(ceil(lo - 0.5)));
  int last = min(uLast, int(ceil(hi - 0.5)));
  return ivec2(first, max(first, last));
}
uint blockEnd(uint b) { return min((b + 1u) * uPerBlock, uTriangleCount); }
)";

const char* const kCount = R"(
layout(local_size_x = 64) in;
void main() {
  uint b = gl_GlobalInvocationID.x;
  if (b >= uBlocks) return;
  for (uint t = b * uPerBlock; t < blockEnd(b); ++t) {
    uvec4 tri = uTriangles[t];
    ivec2 range = scanlineRange(uY[tri.x], uY[tri.y], uY[tri.z]);
    for (int j = range.x; j < range.y; ++j) uCells[uint(j) * uBlocks + b] += 1u;
  }
}
)";

const char* const kFill = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 5) writeonly buffer Slices { uvec4 uSlices[]; };
void main() {
  uint b = gl_GlobalInvocationID.x;
  if (b >= uBlocks) return;
  for (uint t = b * uPerBlock; t < blockEnd(b); ++t) {
    uvec4 tri = uTriangles[t];
    float y[3] = float[3](uY[tri.x], uY[tri.y], uY[tri.z]);
    ivec2 range = scanlineRange(y[0], y[1], y[2]);
    if (range.x >= range.y) continue;
    // Corners sorted by y; the permutation's parity orders the endpoints.
    uint a = 0u, m = 1u, c = 2u;
    bool odd = false;
    if (y[m] < y[a]) { uint s = a; a = m; m = s; odd = !odd; }
    if (y[c] < y[m]) { uint s = m; m = c; c = s; odd = !odd; }
    if (y[m] < y[a]) { uint s = a; a = m; m = s; odd = !odd; }
    float ya = y[a], yb = y[m], yc = y[c];
    uint corners = a | (m << 2) | (c << 4) | (odd ? 0u : 128u);
    for (int j = range.x; j < range.y; ++j) {
      float yy = float(j) + 0.5;
      bool lower = yy >= yb;
      float tShort = lower ? (yy - yb) / (yc - yb) : (yy - ya) / (yb - ya);
      uint cell = uint(j) * uBlocks + b, at = uCells[cell];
      uCells[cell] = at + 1u;
      // Every edge in one form, as the CPU's (no cracks along shared edges).
      uSlices[at] = uvec4(t, floatBitsToUint((yy - ya) / (yc - ya)), floatBitsToUint(tShort),
                          corners | (lower ? 64u : 0u));
    }
  }
}
)";

gl::Program compute(const char* name, const char* main) {
  return gl::linkProgram(name, {{GL_COMPUTE_SHADER, gl::glslHeader() + kCommon + main}});
}

// Grid cells at most: blocks x height stays within this.
constexpr size_t kMaxCells = size_t(1) << 22;
constexpr uint32_t kMinPerBlock = 32;

uint32_t groups(size_t n) { return uint32_t((n + 63) / 64); }

}  // namespace

GpuSlicer::GpuSlicer()
    : count_(compute("slice-count", kCount)), fill_(compute("slice-fill", kFill)) {}

GpuSliceTable GpuSlicer::build(const ExtremeVertices& v, int height, IndexRange lines) {
  std::vector<glm::uvec4> indices(v.triangles.size());
  for (size_t t = 0; t < indices.size(); ++t) indices[t] = glm::uvec4(v.triangles[t], 0u);
  const gl::Buffer ys = gl::makeBuffer(v.y.data(), v.y.size());
  const gl::Buffer tris = gl::makeBuffer(indices.data(), indices.size());
  return build(ys.id(), tris.id(), uint32_t(indices.size()), height, lines);
}

GpuSliceTable GpuSlicer::build(GLuint ys, GLuint tris, uint32_t triangles, int height, IndexRange lines) {
  if (height < 1) fail("GpuSlicer", "height must be at least 1");
  if (lines.begin < 0 || lines.end > height || lines.size() < 0) fail("GpuSlicer", "scanlines outside the image");
  const auto blocks = uint32_t(std::clamp<size_t>(triangles / kMinPerBlock, 1, std::max<size_t>(1, kMaxCells / height)));
  const uint32_t perBlock = std::max<uint32_t>(1, (triangles + blocks - 1) / blocks);
  const size_t cellCount = size_t(blocks) * height;

  gl::Buffer cells = gl::makeBuffer<uint32_t>(nullptr, cellCount, GL_DYNAMIC_STORAGE_BIT);
  cells.fill(cellCount);
  gl::Buffer offsets = gl::makeBuffer<uint32_t>(nullptr, size_t(height) + 1);

  auto use = [&](const gl::Program& p) {
    p.use();
    gl::setUniform(p, "uTriangleCount", GLuint(triangles));
    gl::setUniform(p, "uBlocks", GLuint(blocks));
    gl::setUniform(p, "uPerBlock", GLuint(perBlock));
    gl::setUniform(p, "uFirst", lines.begin);
    gl::setUniform(p, "uLast", lines.end);
    gl::bindStorage(0, ys);
    gl::bindStorage(1, tris);
    cells.bindStorage(2);
  };
  gl::MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);  // the clear
  use(count_);
  gl::dispatch(groups(blocks), 1, 1);
  // offsets[j]: the first slot of scanline j's first cell; offsets[height]:
  // the slice count.
  prefixSum_.exclusiveRows(cells.id(), uint32_t(height), blocks, offsets.id());

  // The one readback: height + 1 offsets, for the slices buffer's size and
  // the rasterizer's batches.
  std::vector<uint32_t> hostOffsets(size_t(height) + 1);
  offsets.read(0, GLsizeiptr(hostOffsets.size() * sizeof(uint32_t)), hostOffsets.data());
  gl::Buffer slices = gl::makeBuffer<Slice>(nullptr, hostOffsets.back());
  if (hostOffsets.back() > 0) {
    use(fill_);
    slices.bindStorage(5);
    gl::dispatch(groups(blocks), 1, 1);
  }
  gl::checkError("GPU slicing");
  return GpuSliceTable::adopt(std::move(slices), std::move(offsets), std::move(hostOffsets));
}

}  // namespace mvr
