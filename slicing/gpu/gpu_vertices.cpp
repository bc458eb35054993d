#include "slicing/gpu/gpu_vertices.h"

#include <algorithm>
#include <bit>
#include <vector>

namespace mvr {

GpuVertices GpuVertices::upload(const ExtremeVertices& v) {
  GpuVertices out;
  const int extras = v.extraCount;
  out.recordStride = kRecordHead + extras;
  out.vertexCount = v.vertexCount();
  out.triangleCount = v.triangles.size();
  std::vector<float> records(out.vertexCount * size_t(out.recordStride));
  for (size_t i = 0; i < out.vertexCount; ++i) {
    float* r = records.data() + i * out.recordStride;
    const float head[kRecordHead] = {v.x0[i], v.dx[i], v.depth[i], v.invW[i],
                                     v.frontOverW[i].r, v.frontOverW[i].g, v.frontOverW[i].b,
                                     v.backOverW[i].r, v.backOverW[i].g, v.backOverW[i].b};
    std::copy_n(head, kRecordHead, r);
    std::copy_n(v.extrasOverW.data() + i * extras, extras, r + kRecordHead);
  }
  std::vector<glm::uvec4> triangles(out.triangleCount);
  for (size_t t = 0; t < triangles.size(); ++t) {
    const uint32_t material = v.materials.empty() ? 0 : v.materials[t];
    triangles[t] = packTriangle(v.triangles[t], material, !v.cullBack.empty() && v.cullBack[t]);
  }
  out.records = gl::makeBuffer(records.data(), records.size());
  out.triangles = gl::makeBuffer(triangles.data(), triangles.size());
  if (!v.vectors.empty()) {
    std::vector<glm::uvec4> vectors(v.vectors.size());
    for (size_t t = 0; t < vectors.size(); ++t) {
      const SliceVector& s = v.vectors[t];
      vectors[t] = glm::uvec4(uint32_t(s.base), uint32_t(s.length), std::bit_cast<uint32_t>(s.u0),
                              std::bit_cast<uint32_t>(s.u1));
    }
    const auto& texels = v.vectorTexels.texels();
    out.vectors = gl::makeBuffer(vectors.data(), vectors.size());
    out.ownedTexels = gl::makeBuffer(texels.data(), std::max<size_t>(1, texels.size()));
    out.texelBuffer = out.ownedTexels.id();
    out.texelCount = texels.size();
  }
  return out;
}

}  // namespace mvr
