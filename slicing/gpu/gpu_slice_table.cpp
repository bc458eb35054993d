#include "slicing/gpu/gpu_slice_table.h"

namespace mvr {

GpuSliceTable GpuSliceTable::upload(const SliceTable& table) {
  const auto slices = table.slices();
  const auto offsets = table.offsets();
  return GpuSliceTable(gl::makeBuffer(slices.data(), slices.size()),
                       gl::makeBuffer(offsets.data(), offsets.size()),
                       std::vector<uint32_t>(offsets.begin(), offsets.end()));
}

SliceTable GpuSliceTable::download() const {
  std::vector<uint32_t> offsets(size_t(height_) + 1);
  std::vector<Slice> slices(count_);
  offsets_.read(0, GLsizeiptr(offsets.size() * sizeof(uint32_t)), offsets.data());
  if (count_ > 0)
    slices_.read(0, GLsizeiptr(count_ * sizeof(Slice)), slices.data());
  return SliceTable::fromArrays(std::move(offsets), std::move(slices));
}

void GpuSliceTable::bind(GLuint slicesBinding, GLuint offsetsBinding) const {
  slices_.bindStorage(slicesBinding);
  offsets_.bindStorage(offsetsBinding);
}

}  // namespace mvr
