#pragma once
// Keeps every frame a renderer produces, for tests.
#include <map>
#include <utility>

#include "mvr/renderer.h"

namespace mvr::test {

class CaptureSink final : public FrameSink {
 public:
  std::map<std::pair<int, int>, Image> views, epis;
  void putView(int row, int view, const Image& image) override { views[{row, view}] = image; }
  void putEpi(int row, int scanline, const Image& epi) override { epis[{row, scanline}] = epi; }
};

}  // namespace mvr::test
