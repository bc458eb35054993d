#pragma once
// Keeps a few views of a render, whichever order it arrives in: the
// benchmark's error measurement without holding the whole view set.
#include <map>
#include <vector>

#include "mvr/renderer.h"

namespace mvr::app {

class SampleSink final : public FrameSink {
 public:
  SampleSink(const std::vector<int>& views, int width, int height, PixelType type);
  void putView(int row, int view, const Image& image) override;
  void putEpi(int row, int scanline, const Image& epi) override;
  const std::map<int, Image>& samples() const { return samples_; }

 private:
  std::map<int, Image> samples_;  // row 0 only
};

// count views spread evenly over 0..views-1, always with the first and last.
std::vector<int> spreadViews(int views, int count);

}  // namespace mvr::app
