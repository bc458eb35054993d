#pragma once
// The slice table resident in GPU memory: the same 16-byte entries and
// height + 1 offsets as SliceTable, in two shader storage buffers, for the
// passes that slice and build PSTs on the GPU (compute, vertex pulling).
// Upload and download make the CPU slicer's table and a GPU-built one
// interchangeable, so the CPU slicer stays the oracle.
#include <cstddef>

#include "mvr/gl/gl_handles.h"
#include "slicing/slice_table.h"

namespace mvr {

class GpuSliceTable {
 public:
  // Needs a current GL context.
  static GpuSliceTable upload(const SliceTable& table);
  SliceTable download() const;

  int height() const { return height_; }
  size_t sliceCount() const { return count_; }
  GLuint slicesBuffer() const { return slices_.id(); }
  GLuint offsetsBuffer() const { return offsets_.id(); }
  // Both buffers to shader storage binding points.
  void bind(GLuint slicesBinding, GLuint offsetsBinding) const;

 private:
  GpuSliceTable(gl::Buffer slices, gl::Buffer offsets, int height, size_t count)
      : slices_(std::move(slices)), offsets_(std::move(offsets)), height_(height), count_(count) {}
  gl::Buffer slices_, offsets_;
  int height_ = 0;
  size_t count_ = 0;
};

}  // namespace mvr
