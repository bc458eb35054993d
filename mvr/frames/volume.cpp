#include "mvr/frames/volume.h"

#include <algorithm>
#include <cstring>

#include "mvr/error.h"
#include "mvr/parallel.h"

namespace mvr {
namespace {

std::span<const std::byte> bytesOf(const Image& image) {
  return std::as_bytes(std::span(image.bytes));
}

}  // namespace

FrameTranspose::FrameTranspose(int inputs, int rowsPerInput, int width, PixelType type,
                               const ReorderMemory& memory)
    : inputs_(inputs), rowsPerInput_(rowsPerInput),
      inputBytes_(size_t(width) * 4 * Image::channelBytes(type) * size_t(rowsPerInput)),
      rowBytes_(size_t(width) * 4 * Image::channelBytes(type)) {
  const size_t outputBytes = rowBytes_ * size_t(inputs);
  int held = rowsPerInput;
  if (memory.spills(outputBytes * size_t(rowsPerInput))) {
    // At least one output frame, however small the budget.
    held = int(std::clamp<size_t>(memory.budget / outputBytes, 1, size_t(rowsPerInput)));
    scratch_ = std::make_unique<ScratchFile>(memory.scratchDir);
  }
  // Made on the pool: a volume's first touch (1.2 GB at 640x480 x 1000
  // views) is page faults and zero-fill that one thread pays in full.
  outputs_.resize(size_t(held));
  parallelFor(0, held, [&](int k) { outputs_[size_t(k)] = Image(width, inputs, type); });
}

bool FrameTranspose::put(int index, const Image& frame) {
  if (index < 0 || index >= inputs_ || frame.bytes.size() != inputBytes_)
    fail("reordering sink", "a frame of the wrong shape or index");
  if (scratch_) {
    scratch_->write(uint64_t(index) * inputBytes_, bytesOf(frame));
  } else {
    // Each row goes to another output: runs of rows on the pool.
    constexpr int kRun = 64;
    parallelFor(0, (rowsPerInput_ + kRun - 1) / kRun, [&](int run) {
      for (int j = run * kRun; j < std::min(rowsPerInput_, (run + 1) * kRun); ++j)
        std::memcpy(outputs_[size_t(j)].row(index), frame.row(j), rowBytes_);
    });
  }
  return ++received_ == inputs_;
}

void FrameTranspose::emit(const std::function<void(int, const Image&)>& out) {
  received_ = 0;
  if (scratch_) return emitFromScratch(out);
  for (int j = 0; j < rowsPerInput_; ++j) out(j, outputs_[size_t(j)]);
}

// A pass fills a group of outputs: from every input, the run of rows the
// group needs, read in one call straight into the outputs' rows.
void FrameTranspose::emitFromScratch(const std::function<void(int, const Image&)>& out) {
  const int group = int(outputs_.size());
  std::vector<std::span<std::byte>> pieces;
  for (int first = 0; first < rowsPerInput_; first += group) {
    const int n = std::min(group, rowsPerInput_ - first);
    for (int i = 0; i < inputs_; ++i) {
      pieces.clear();
      for (int k = 0; k < n; ++k)
        pieces.push_back(std::as_writable_bytes(std::span(outputs_[size_t(k)].row(i), rowBytes_)));
      scratch_->read(uint64_t(i) * inputBytes_ + uint64_t(first) * rowBytes_, pieces);
    }
    for (int k = 0; k < n; ++k) out(first + k, outputs_[size_t(k)]);
  }
}

std::string FrameTranspose::scratchNote() const {
  if (!scratch_) return "";
  return "; reordered through a scratch file, " + std::to_string(outputs_.size()) + " frames per pass";
}

EpisToViews::EpisToViews(FrameSink& inner, int width, int height, int views, PixelType type,
                         const ReorderMemory& memory)
    : inner_(inner), height_(height), views_(views), volume_(height, views, width, type, memory) {}

void EpisToViews::putEpi(int row, int scanline, const Image& epi) {
  if (epi.height != views_ || scanline < 0 || scanline >= height_) fail("EPI sink", "EPI of the wrong shape");
  row_ = row;
  if (!volume_.put(scanline, epi)) return;
  volume_.emit([&](int view, const Image& image) { inner_.putView(row_, view, image); });
}

ViewsToEpis::ViewsToEpis(FrameSink& inner, int width, int height, int views, PixelType type,
                         const ReorderMemory& memory)
    : inner_(inner), height_(height), views_(views), volume_(views, height, width, type, memory) {}

void ViewsToEpis::putView(int row, int view, const Image& image) {
  if (image.height != height_ || view < 0 || view >= views_) fail("view sink", "view of the wrong shape");
  row_ = row;
  if (!volume_.put(view, image)) return;
  volume_.emit([&](int scanline, const Image& epi) { inner_.putEpi(row_, scanline, epi); });
}

}  // namespace mvr
