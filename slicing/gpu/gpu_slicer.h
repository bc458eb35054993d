#pragma once
// The scanline slice table built on the GPU (Halle 6.4.2 as compute
// passes): the same entries, in the same order, as SliceTable::build, the
// CPU slicer that stays its oracle. Triangles are split into blocks; one
// invocation per block counts its triangles' slices per scanline into a
// scanline-major grid of (scanline, block) cells, a prefix sum over the
// grid gives every cell its first slot, and the same invocations write
// their slices there in triangle order. Per scanline that is block order,
// then triangle order within a block: the CPU's triangle order, with no
// atomics and no sort. Only the height + 1 offsets come back to the host
// (GpuSliceTable keeps them for batching); the slices never do.
#include "mvr/camera.h"
#include "mvr/gl/gl_handles.h"
#include "mvr/gl/prefix_sum.h"
#include "slicing/extreme_vertices.h"
#include "slicing/gpu/gpu_slice_table.h"

namespace mvr {

class GpuSlicer {
 public:
  GpuSlicer();  // needs a current GL context

  // The table of v's triangles over `height` scanlines. Uploads y per
  // vertex and the triangles' indices: O(vertices + triangles).
  GpuSliceTable build(const ExtremeVertices& v, int height) { return build(v, height, {0, height}); }
  // The same with slices in `lines` only: a split job's band (the other
  // scanlines are empty, as in SliceTable::build).
  GpuSliceTable build(const ExtremeVertices& v, int height, IndexRange lines);
  // The same from buffers already on the GPU (GpuExtremeTransform's): y
  // per vertex, and triangles as uvec4 (a, b, c, anything).
  GpuSliceTable build(GLuint ys, GLuint triangles, uint32_t triangleCount, int height, IndexRange lines);
  GpuSliceTable build(GLuint ys, GLuint triangles, uint32_t triangleCount, int height) {
    return build(ys, triangles, triangleCount, height, {0, height});
  }

 private:
  gl::Program count_, fill_;
  gl::PrefixSum prefixSum_;
};

}  // namespace mvr
