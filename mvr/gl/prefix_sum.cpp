#include "mvr/gl/prefix_sum.h"

#include "mvr/gl/gl_program.h"

namespace mvr::gl {
namespace {

// One workgroup scans one block: each of 64 invocations sums its own run
// of 16 consecutive elements, invocation 0 scans the 64 run totals, and
// each invocation writes its run's exclusive sums; the block total goes to
// uSums[block]. Two barriers per block: CPU implementations of GL
// (llvmpipe) pay per barrier, GPUs barely notice the serial parts.
const char* const kScan = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) buffer Data { uint uData[]; };
layout(std430, binding = 1) writeonly buffer Sums { uint uSums[]; };
uniform uint uFirst;
uniform uint uCount;
shared uint sRun[64];
void main() {
  uint t = gl_LocalInvocationID.x, begin = gl_WorkGroupID.x * 1024u + 16u * t;
  uint end = min(begin + 16u, uCount), sum = 0u;
  for (uint i = begin; i < end; ++i) sum += uData[uFirst + i];
  sRun[t] = sum;
  barrier();
  if (t == 0u) {
    uint run = 0u;
    for (uint k = 0u; k < 64u; ++k) {
      uint x = sRun[k];
      sRun[k] = run;
      run += x;
    }
    uSums[gl_WorkGroupID.x] = run;
  }
  barrier();
  uint run = sRun[t];
  for (uint i = begin; i < end; ++i) {
    uint x = uData[uFirst + i];
    uData[uFirst + i] = run;
    run += x;
  }
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
  uint add = uSums[gl_WorkGroupID.x];
  for (uint i = gl_WorkGroupID.x * 1024u + gl_LocalInvocationID.x; i < min((gl_WorkGroupID.x + 1u) * 1024u, uCount); i += 256u)
    uData[uFirst + i] += add;
}
)";

// out[j] = data[j * uStride], the first slot of grid row j after the scan.
const char* const kRowStarts = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Data { uint uData[]; };
layout(std430, binding = 1) writeonly buffer Out { uint uOut[]; };
uniform uint uStride;
uniform uint uRows;
void main() {
  uint j = gl_GlobalInvocationID.x;
  if (j < uRows) uOut[j] = uData[j * uStride];
}
)";

// Shader-storage writes made visible to later shaders, to indirect draws
// and to buffer copies (the total). The copy itself needs no barrier: it
// is an ordinary GL command.
constexpr GLbitfield kBarriers =
    GL_SHADER_STORAGE_BARRIER_BIT | GL_COMMAND_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT;

void setCounts(const Program& p, uint32_t first, uint32_t count) {
  ProgramUniform1ui(p.id(), GetUniformLocation(p.id(), "uFirst"), first);
  ProgramUniform1ui(p.id(), GetUniformLocation(p.id(), "uCount"), count);
}

}  // namespace

PrefixSum::PrefixSum()
    : scan_(linkProgram("prefix-sum", {{GL_COMPUTE_SHADER, glslHeader() + kScan}})),
      add_(linkProgram("prefix-sum-add", {{GL_COMPUTE_SHADER, glslHeader() + kAdd}})),
      rowStarts_(linkProgram("prefix-sum-row-starts", {{GL_COMPUTE_SHADER, glslHeader() + kRowStarts}})) {}

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
  MemoryBarrier(kBarriers);
  if (blocks == 1) return sums;
  const GLuint total = scan(sums, 0, blocks, level + 1);
  UseProgram(add_.id());
  setCounts(add_, first, count);
  BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, data);
  BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, sums);
  DispatchCompute(blocks, 1, 1);
  MemoryBarrier(kBarriers);
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
}

void PrefixSum::exclusiveRows(GLuint data, uint32_t rows, uint32_t stride, GLuint out) {
  exclusive(data, 0, rows * stride, out, GLintptr(rows) * GLintptr(sizeof(uint32_t)));
  if (stride == 0) {  // no counts: every row starts at 0
    const uint32_t zero = 0;
    ClearNamedBufferSubData(out, GL_R32UI, 0, GLsizeiptr(rows * sizeof(uint32_t)), GL_RED_INTEGER,
                            GL_UNSIGNED_INT, &zero);
    return;
  }
  UseProgram(rowStarts_.id());
  ProgramUniform1ui(rowStarts_.id(), GetUniformLocation(rowStarts_.id(), "uStride"), stride);
  ProgramUniform1ui(rowStarts_.id(), GetUniformLocation(rowStarts_.id(), "uRows"), rows);
  BindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, data);
  BindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out);
  DispatchCompute((rows + 63) / 64, 1, 1);
  MemoryBarrier(kBarriers);
}

}  // namespace mvr::gl
