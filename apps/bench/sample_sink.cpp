#include "apps/bench/sample_sink.h"

#include <algorithm>
#include <cstring>

namespace mvr::app {

SampleSink::SampleSink(const std::vector<int>& views, int width, int height, PixelType type) {
  for (int v : views) samples_.emplace(v, Image(width, height, type));
}

void SampleSink::putView(int row, int view, const Image& image) {
  if (row != 0) return;
  if (auto it = samples_.find(view); it != samples_.end()) it->second = image;
}

void SampleSink::putEpi(int row, int scanline, const Image& epi) {
  if (row != 0) return;
  for (auto& [view, image] : samples_)
    std::memcpy(image.row(scanline), epi.row(view), epi.rowBytes());
}

std::vector<int> spreadViews(int views, int count) {
  std::vector<int> out;
  count = std::max(1, std::min(count, views));
  for (int k = 0; k < count; ++k)
    out.push_back(count == 1 ? views / 2 : int((long(views - 1) * k) / (count - 1)));
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace mvr::app
