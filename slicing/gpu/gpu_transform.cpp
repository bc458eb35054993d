#include "slicing/gpu/gpu_transform.h"

#include <algorithm>
#include <string>
#include <vector>

#include "mvr/error.h"
#include "mvr/gl/gl_program.h"
#include "mvr/parallel.h"

namespace mvr {
namespace {

// ExtremeTransform::add, term for term.
const char* const kTransform = R"(
layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Positions { float uPositions[]; };  // xyz
layout(std430, binding = 1) readonly buffer Shading { float uShading[]; };  // front, back, extras
layout(std430, binding = 2) writeonly buffer Records { float uRecords[]; };
layout(std430, binding = 3) writeonly buffer Ys { float uY[]; };
uniform uint uCount;
uniform int uExtras;
uniform double uD, uNear, uFar, uSx, uSy, uCxLeft, uCxRight, uCy, uWidth, uHeight;
uniform int uViews;

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= uCount) return;
  dvec3 p = dvec3(uPositions[3u * i], uPositions[3u * i + 1u], uPositions[3u * i + 2u]);
  double w = uD - p.z;
  double xl = (uSx * (uD * p.x - uCxLeft * p.z) / w + 1.0) * 0.5 * uWidth;
  double xr = (uSx * (uD * p.x - uCxRight * p.z) / w + 1.0) * 0.5 * uWidth;
  double y = (-uSy * (uD * p.y - uCy * p.z) / w + 1.0) * 0.5 * uHeight;
  uint stride = uint(10 + uExtras), at = i * stride, from = i * uint(6 + uExtras);
  float invW = float(1.0 / w);
  uRecords[at] = float(xl);
  uRecords[at + 1u] = uViews > 1 ? float((xr - xl) / double(uViews - 1)) : 0.0;
  uRecords[at + 2u] = float(uNear * (uFar - w) / ((uFar - uNear) * w));
  uRecords[at + 3u] = invW;
  for (uint k = 0u; k < uint(6 + uExtras); ++k) uRecords[at + 4u + k] = uShading[from + k] * invW;
  uY[i] = float(y);
}
)";

}  // namespace

namespace {

void checkSizes(const Scene& scene, const shading::VertexColors& colors, std::span<const float> extras,
                int extraCount) {
  const size_t n = scene.vertexCount();
  if (colors.front.size() != n || colors.back.size() != n || extras.size() != n * size_t(extraCount))
    fail("GpuExtremeTransform", "colours or extras do not match the scene's vertices");
}

// Per vertex: the lit front and back colours, then the extras.
std::vector<float> packShading(const shading::VertexColors& colors, std::span<const float> extras, int extraCount) {
  const size_t n = colors.front.size();
  std::vector<float> shading(n * size_t(6 + extraCount));
  parallelChunks(n, 16384, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      float* s = shading.data() + i * (6 + extraCount);
      const float head[6] = {colors.front[i].r, colors.front[i].g, colors.front[i].b,
                             colors.back[i].r,  colors.back[i].g,  colors.back[i].b};
      std::copy_n(head, 6, s);
      std::copy_n(extras.data() + i * extraCount, extraCount, s + 6);
    }
  });
  return shading;
}

}  // namespace

GpuExtremeTransform::GpuExtremeTransform(const Scene& scene, const shading::VertexColors& colors,
                                         std::span<const float> extras, int extraCount)
    : extraCount_(extraCount) {
  checkSizes(scene, colors, extras, extraCount);
  const size_t n = scene.vertexCount();
  program_ = gl::linkProgram("extreme-transform", {{GL_COMPUTE_SHADER, gl::glslHeader() + kTransform}});
  const std::vector<float> shading = packShading(colors, extras, extraCount);
  // Written again when the scene moves (moved()).
  positions_ = gl::makeBuffer(reinterpret_cast<const float*>(scene.positions.data()), 3 * n, GL_DYNAMIC_STORAGE_BIT);
  shading_ = gl::makeBuffer(shading.data(), shading.size(), GL_DYNAMIC_STORAGE_BIT);
  y_ = gl::makeBuffer<float>(nullptr, n);
  std::vector<glm::uvec4> triangles(scene.triangleCount());
  for (size_t t = 0; t < triangles.size(); ++t) {
    const uint32_t material = scene.materialIds[t];
    triangles[t] = GpuVertices::packTriangle(scene.triangles[t], material, !scene.materials[material].twoSided);
  }
  vertices_.recordStride = GpuVertices::kRecordHead + extraCount;
  vertices_.vertexCount = n;
  vertices_.triangleCount = triangles.size();
  vertices_.records = gl::makeBuffer<float>(nullptr, n * size_t(vertices_.recordStride));
  vertices_.triangles = gl::makeBuffer(triangles.data(), triangles.size());
  gl::checkError("uploading the scene for the GPU transform");
}

void GpuExtremeTransform::moved(const Scene& scene, const shading::VertexColors& colors,
                                std::span<const float> extras) {
  checkSizes(scene, colors, extras, extraCount_);
  if (scene.vertexCount() != vertices_.vertexCount || scene.triangleCount() != vertices_.triangleCount)
    fail("GpuExtremeTransform", "the moved scene has other vertices or triangles");
  const std::vector<float> shading = packShading(colors, extras, extraCount_);
  positions_.write(0, scene.positions.size() * sizeof(scene.positions[0]), scene.positions.data());
  shading_.write(0, shading.size() * sizeof(float), shading.data());
  gl::checkError("uploading the moved scene for the GPU transform");
}

bool GpuExtremeTransform::needsNoClipping(const Bounds& b, const ShearingCamera& cam) {
  const CameraSpec& s = cam.spec();
  // ExtremeTransform::inside for the nearest and farthest vertex.
  return s.distance - double(b.max.z) >= s.nearDistance && s.distance - double(b.min.z) <= s.farDistance;
}

const GpuVertices& GpuExtremeTransform::transform(const ShearingCamera& cam, int row) {
  const CameraSpec& s = cam.spec();
  auto set = [&](const char* name, double v) { gl::setUniform(program_, name, v); };
  set("uD", s.distance);
  set("uNear", s.nearDistance);
  set("uFar", s.farDistance);
  set("uSx", 2.0 / cam.planeWidth());
  set("uSy", 2.0 / cam.planeHeight());
  set("uCxLeft", cam.viewX(0));
  set("uCxRight", cam.viewX(cam.views() - 1));
  set("uCy", cam.rowY(row));
  set("uWidth", cam.width());
  set("uHeight", cam.height());
  gl::setUniform(program_, "uViews", cam.views());
  gl::setUniform(program_, "uExtras", extraCount_);
  gl::setUniform(program_, "uCount", GLuint(vertices_.vertexCount));
  program_.use();
  positions_.bindStorage(0);
  shading_.bindStorage(1);
  vertices_.records.bindStorage(2);
  y_.bindStorage(3);
  gl::dispatch(uint32_t((vertices_.vertexCount + 63) / 64), 1, 1);
  gl::checkError("GPU extreme transform");
  return vertices_;
}

}  // namespace mvr
