#pragma once
// The slice table as the EPI rasterizers receive it: in host memory (the
// CPU slicer's) or in GPU buffers (a GPU slicer's). A rasterizer asks for
// the form it reads; the other form is made once on demand (a download or
// an upload) and kept for the view's lifetime. Callers pass whichever they
// built, so a GPU slicer plugs in without touching them.
#include <optional>

#include "slicing/gpu/gpu_slice_table.h"
#include "slicing/slice_table.h"

namespace mvr {

class SliceTableView {
 public:
  SliceTableView(const SliceTable& host) : host_(&host) {}          // NOLINT: implicit by design
  SliceTableView(const GpuSliceTable& device) : device_(&device) {}  // NOLINT: implicit by design
  SliceTableView(const SliceTableView&) = delete;
  SliceTableView& operator=(const SliceTableView&) = delete;

  bool onHost() const { return host_ != nullptr; }
  bool onDevice() const { return device_ != nullptr; }
  int height() const { return host_ ? host_->height() : device_->height(); }
  size_t sliceCount() const { return host_ ? host_->sliceCount() : device_->sliceCount(); }

  // The host arrays; downloads once when the table lives on the GPU.
  const SliceTable& host() const {
    if (host_) return *host_;
    if (!downloaded_) downloaded_ = device_->download();
    return *downloaded_;
  }
  // The GPU buffers; uploads once when the table lives on the host. Needs
  // a current GL context.
  const GpuSliceTable& device() const {
    if (device_) return *device_;
    if (!uploaded_) uploaded_ = GpuSliceTable::upload(*host_);
    return *uploaded_;
  }

 private:
  const SliceTable* host_ = nullptr;
  const GpuSliceTable* device_ = nullptr;
  mutable std::optional<SliceTable> downloaded_;
  mutable std::optional<GpuSliceTable> uploaded_;
};

}  // namespace mvr
