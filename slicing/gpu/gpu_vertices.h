#pragma once
// The extreme vertices resident in GPU memory, in the layout the PST passes
// pull from (epi/gpu/pst_geometry.h): one float record per vertex, one
// uvec4 per triangle and, for slices coloured by their own texture
// vectors, one uvec4 per triangle and the vectors' texels. Uploaded from
// ExtremeVertices, or written in place by a GPU pass (the image-based
// back end's slicer), so the PST passes never see which.
#include <cstddef>

#include "mvr/gl/gl_handles.h"
#include "slicing/extreme_vertices.h"

namespace mvr {

struct GpuVertices {
  // Floats per record before the extras: x0, dx, depth, 1/w, front colour
  // / w, back colour / w; then ExtremeVertices::extraCount extras / w.
  static constexpr int kRecordHead = 10;

  int recordStride = kRecordHead;
  size_t vertexCount = 0, triangleCount = 0;
  gl::Buffer records;    // recordStride floats per vertex
  gl::Buffer triangles;  // uvec4: a, b, c, material | cull << 31
  // Per triangle (base, level-0 length, u0 bits, u1 bits) of its vector
  // (SliceVector), and the texels they index; texelBuffer is
  // ownedTexels or a buffer of the writer's (a layer store). Both 0 when
  // slices are not coloured by vectors.
  gl::Buffer vectors;
  gl::Buffer ownedTexels;
  GLuint texelBuffer = 0;
  size_t texelCount = 0;

  bool hasVectors() const { return texelBuffer != 0; }

  // One entry of `triangles`.
  static glm::uvec4 packTriangle(const glm::uvec3& corners, uint32_t material, bool cullBack) {
    return glm::uvec4(corners, material | (cullBack ? 1u << 31 : 0u));
  }

  // Needs a current GL context. O(vertices + triangles + texels); the
  // highlight knots are not uploaded (their passes read host vertices).
  static GpuVertices upload(const ExtremeVertices& v);
};

}  // namespace mvr
