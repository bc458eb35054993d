#pragma once
// Renders a scene with a named back end into memory, as views.
#include <memory>

#include "epi/mvr_renderer.h"
#include "epi/volume.h"
#include "mvr/baselines.h"
#include "mvr/compare.h"
#include "tests/support/capture_sink.h"
#include "tests/support/gl_fixture.h"

namespace mvr::test {

inline CaptureSink renderViews(Renderer& renderer, const ShearingCamera& cam,
                               PixelType type = PixelType::U8) {
  CaptureSink capture;
  EpisToViews reorder(capture, cam.width(), cam.height(), cam.views(), type);
  FrameSink& sink = renderer.order() == FrameOrder::Epi ? static_cast<FrameSink&>(reorder) : capture;
  RenderStats stats;
  renderer.render(cam, sink, stats);
  return capture;
}

struct SetDifference {
  double minPsnr = INFINITY, minIdentical = 1.0;
};

inline SetDifference compareViews(const CaptureSink& a, const CaptureSink& b) {
  SetDifference d;
  EXPECT_EQ(a.views.size(), b.views.size());
  for (const auto& [key, img] : a.views) {
    ImageDifference x = compareImages(img, b.views.at(key));
    d.minPsnr = std::min(d.minPsnr, x.psnr);
    d.minIdentical = std::min(d.minIdentical, x.identicalFraction);
  }
  return d;
}

}  // namespace mvr::test
