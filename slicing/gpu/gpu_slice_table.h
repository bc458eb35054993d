#pragma once
// The slice table resident in GPU memory: the same 16-byte entries and
// height + 1 offsets as SliceTable, in two shader storage buffers, for the
// passes that slice and build PSTs on the GPU (compute, vertex pulling).
// Upload and download make the CPU slicer's table and a GPU-built one
// interchangeable, so the CPU slicer stays the oracle.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "mvr/gl/gl_handles.h"
#include "slicing/slice_table.h"

namespace mvr {

class GpuSliceTable {
 public:
  // Needs a current GL context.
  static GpuSliceTable upload(const SliceTable& table);
  // A table a GPU pass built: its buffers and the offsets on the host.
  static GpuSliceTable adopt(gl::Buffer slices, gl::Buffer offsets, std::vector<uint32_t> hostOffsets) {
    return GpuSliceTable(std::move(slices), std::move(offsets), std::move(hostOffsets));
  }
  SliceTable download() const;

  int height() const { return height_; }
  size_t sliceCount() const { return count_; }
  GLuint slicesBuffer() const { return slices_.id(); }
  GLuint offsetsBuffer() const { return offsets_.id(); }
  // The height + 1 offsets, also kept on the host (O(height)): callers
  // batch scanlines by slice ranges without touching the slices.
  const std::vector<uint32_t>& offsets() const { return hostOffsets_; }
  // Both buffers to shader storage binding points.
  void bind(GLuint slicesBinding, GLuint offsetsBinding) const;

 private:
  GpuSliceTable(gl::Buffer slices, gl::Buffer offsets, std::vector<uint32_t> hostOffsets)
      : slices_(std::move(slices)), offsets_(std::move(offsets)),
        hostOffsets_(std::move(hostOffsets)), height_(int(hostOffsets_.size()) - 1),
        count_(hostOffsets_.back()) {}
  gl::Buffer slices_, offsets_;
  std::vector<uint32_t> hostOffsets_;
  int height_ = 0;
  size_t count_ = 0;
};

}  // namespace mvr
