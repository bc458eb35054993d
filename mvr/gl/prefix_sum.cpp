#include "mvr/gl/prefix_sum.h"

#include "mvr/gl/gl_program.h"

namespace mvr::gl {
namespace {

// One workgroup scans one block of 512 elements in shared memory (two per
// invocation): up-sweep to the block total, then down-sweep to exclusive
// sums; the block total goes to uSums[block].
const char* const kScan = R"(
layout(local_size_x = 256) in;
layout(std430, binding = 0) buffer Data { uint uData[]; };
layout(std430, binding = 1) writeonly buffer Sums { uint uSums[]; };
uniform uint uFirst;
uniform uint uCount;
shared uint s[512];
void main() {
  uint t = gl_LocalInvocationID.x, i = gl_WorkGroupID.x * 512u + 2u * t;
  s[2u * t] = i < uCount ? uData[uFirst + i] : 0u;
  s[2u * t + 1u] = i + 1u < uCount ? uData[uFirst + i + 1u] : 0u;
  uint offset = 1u;
  for (uint d = 256u; d > 0u; d >>= 1u, offset <<= 1u) {
    barrier();
    if (t < d) s[offset * (2u * t + 2u) - 1u] += s[offset * (2u * t + 1u) - 1u];
  }
  barrier();
  if (t == 0u) {
    uSums[gl_WorkGroupID.x] = s[511];
    s[511] = 0u;
  }
  for (uint d = 1u; d < 512u; d <<= 1u) {
    offset >>= 1u;
    barrier();
    if (t < d) {
      uint a = offset * (2u * t + 1u) - 1u, b = offset * (2u * t + 2u) - 1u;
      uint x = s[a];
      s[a] = s[b];
      s[b] += x;
    }
  }
  barrier();
  if (i < uCount) uData[uFirst + i] = s[2u * t];
  if (i + 1u < uCount) uData[uFirst + i + 1u] = s[2u * t + 1u];
}
)";

// Adds each block's offset (the scanned block totals) to its elements.
const char* const kAdd = R"(
layout(local_size_x = 256) in;
layout(std430, binding = 0) buffer Data { uint uData[]; };
layout(std430, binding = 1) readonly buffer Sums { uint uSums[]; };
uniform uint uFirst;
uniform uint uCount;
void main() {
  uint i = gl_WorkGroupID.x * 512u + gl_LocalInvocationID.x;
  uint add = uSums[gl_WorkGroupID.x];
  if (i < uCount) uData[uFirst + i] += add;
  if (i + 256u < uCount) uData[uFirst + i + 256u] += add;
}
)";

void setCounts(const Program& p, uint32_t first, uint32_t count) {
  ProgramUniform1ui(p.id(), GetUniformLocation(p.id(), "uFirst"), first);
  ProgramUniform1ui(p.id(), GetUniformLocation(p.id(), "uCount"), count);
}

}  // namespace

PrefixSum::PrefixSum()
    : scan_(linkProgram("prefix-sum", {{GL_COMPUTE_SHADER, glslHeader() + kScan}})),
      add_(linkProgram("prefix-sum-add", {{GL_COMPUTE_SHADER, glslHeader() + kAdd}})) {}

GLuint PrefixSum::scan(GLuint data, uint32_t first, uint32_t count, size_t level) {
  const uint32_t blocks = (count + kBlock - 1) / kBlock;
  if (sums_.size() <= level) {
    sums_.resize(level + 1);
    sumsSize_.resize(level + 1, 0);
  }
  if (sumsSize_[level] < blocks) {
    sums_[level] = Buffer::create();
    NamedBufferStorage(sums_[level].id(), GLsizeiptr(blocks * sizeof(uint32_t)), nullptr, 0);
    sumsSize_[level] = blocks;
  }
  const GLuint sums = sums_[level].id();
  UseProgram(scan_.id());
  setCounts(scan_, first, count);
  BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, data);
  BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, sums);
  DispatchCompute(blocks, 1, 1);
  MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  if (blocks == 1) return sums;
  const GLuint total = scan(sums, 0, blocks, level + 1);
  UseProgram(add_.id());
  setCounts(add_, first, count);
  BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, data);
  BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, sums);
  DispatchCompute(blocks, 1, 1);
  MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
  return total;
}

void PrefixSum::exclusive(GLuint data, uint32_t first, uint32_t count, GLuint totalBuffer,
                          GLintptr totalAt) {
  if (count == 0) {
    const uint32_t zero = 0;
    ClearNamedBufferSubData(totalBuffer, GL_R32UI, totalAt, sizeof zero, GL_RED_INTEGER,
                            GL_UNSIGNED_INT, &zero);
  } else {
    const GLuint total = scan(data, first, count, 0);
    CopyNamedBufferSubData(total, totalBuffer, 0, totalAt, sizeof(uint32_t));
  }
  MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

}  // namespace mvr::gl
