#pragma once
// The EPIs of a batch of scanlines a GL rasterizer reads back: each in
// memory its sink lends (FrameSink::epiMemory), filled there and not
// handed on, or in an image of the rasterizer's pool, handed on in
// scanline order once the batch's reads have landed.
#include <algorithm>
#include <cstddef>
#include <memory>
#include <vector>

#include "mvr/image_pool.h"
#include "mvr/parallel.h"
#include "mvr/renderer.h"

namespace mvr {

class EpiBatch {
 public:
  EpiBatch(FrameSink& sink, ImagePool& pool, int row, IndexRange scanlines, int width, int views, PixelType type)
      : row_(row), first_(scanlines.begin), rowBytes_(size_t(width) * 4 * Image::channelBytes(type)) {
    int owned = 0;
    for (int j = scanlines.begin; j < scanlines.end; ++j) {
      memory_.push_back(sink.epiMemory(row, j, width, views, type));
      owned += memory_.back() == nullptr;
    }
    std::vector<std::shared_ptr<Image>> images = pool.take(owned, width, views, type);
    own_.resize(memory_.size());
    for (size_t k = 0, next = 0; k < memory_.size(); ++k)
      if (!memory_[k]) own_[k] = images[next++], memory_[k] = own_[k]->row(0);
  }

  int size() const { return int(memory_.size()); }
  // EPI k's rows from view `view` on: where its reads land.
  std::byte* rows(int k, int view) const { return reinterpret_cast<std::byte*>(memory_[size_t(k)] + view * rowBytes_); }
  std::vector<std::byte*> rows(int view) const {
    std::vector<std::byte*> out;
    for (int k = 0; k < size(); ++k) out.push_back(rows(k, view));
    return out;
  }
  // The EPIs that are the rasterizer's own to the sink, in scanline order.
  void handOn(FrameSink& sink) const {
    for (size_t k = 0; k < own_.size(); ++k)
      if (own_[k]) sink.putEpiInPlace(row_, first_ + int(k), *own_[k]);
  }

 private:
  int row_, first_;
  size_t rowBytes_;
  std::vector<uint8_t*> memory_;             // each EPI's first row
  std::vector<std::shared_ptr<Image>> own_;  // null where the sink lent memory
};

// The CPU's way: fill(scanline, rows) fills each EPI of one row of views
// on the pool's workers, up to a window ahead while the caller hands them
// on in scanline order (a sink's copies would otherwise leave the workers
// idle); no batch barrier, so a dense scanline holds up nobody. EPIs the
// sink lends memory for are filled there and not handed on; the others in
// the window's images, `ring`, allocated once and kept by the caller for
// its next row and render: fresh multi-megabyte images per scanline cost
// page faults that serialise on the kernel's memory lock (at 1920x1080 x
// 1000 views a fresh set cost 0.27 s a call).
template <class Fill>
void fillEpisInOrder(FrameSink& sink, int row, IndexRange lines, int width, int views, PixelType type,
                     std::vector<Image>& ring, Fill&& fill) {
  const int window = std::max(1, std::min(lines.size(), 2 * threadCount()));
  const bool fits = !ring.empty() && ring[0].width == width && ring[0].height == views && ring[0].type == type;
  if (!fits) ring.clear();
  ring.resize(std::max(ring.size(), size_t(window)), Image(width, views, type));
  std::vector<uint8_t*> memory(size_t(lines.size()));
  for (int j = lines.begin; j < lines.end; ++j) memory[size_t(j - lines.begin)] = sink.epiMemory(row, j, width, views, type);
  parallelOrdered(
      lines.begin, lines.end, window,
      [&](int j) {
        uint8_t* lent = memory[size_t(j - lines.begin)];
        fill(j, lent ? PixelRows(lent, width, views, type) : PixelRows(ring[size_t(j - lines.begin) % window]));
      },
      [&](int j) {
        if (!memory[size_t(j - lines.begin)]) sink.putEpiInPlace(row, j, ring[size_t(j - lines.begin) % window]);
      });
}

}  // namespace mvr
