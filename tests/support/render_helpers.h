#pragma once
// Renders a scene with a named back end into memory, as views.
#include <cstdlib>
#include <map>
#include <memory>
#include <string>

#include "epi/mvr_renderer.h"
#include "epi/volume.h"
#include "mvr/baselines/baselines.h"
#include "mvr/io/compare.h"
#include "mvr/io/image_file.h"
#include "tests/support/capture_sink.h"
#include "tests/support/gl_fixture.h"

namespace mvr::test {

// stats: the renderer's stats, for tests that check passes or counters.
inline CaptureSink renderViews(Renderer& renderer, const ShearingCamera& cam, RenderStats& stats,
                               PixelType type = PixelType::U8) {
  CaptureSink capture;
  EpisToViews reorder(capture, cam.width(), cam.height(), cam.views(), type);
  FrameSink& sink = renderer.order() == FrameOrder::Epi ? static_cast<FrameSink&>(reorder) : capture;
  renderer.render(cam, sink, stats);
  return capture;
}

inline CaptureSink renderViews(Renderer& renderer, const ShearingCamera& cam,
                               PixelType type = PixelType::U8) {
  RenderStats stats;
  return renderViews(renderer, cam, stats, type);
}

struct SetDifference {
  double minPsnr = INFINITY, minIdentical = 1.0, minClose = 1.0;
};

// Set MVR_TEST_DUMP=DIR to keep the images a failing comparison looked at.
inline void dumpPair(const Image& a, const Image& b, int view) {
  static int serial = 0;
  const char* dir = std::getenv("MVR_TEST_DUMP");
  if (!dir) return;
  const std::string base = std::string(dir) + "/" + std::to_string(serial) + "_v" + std::to_string(view);
  writeImage(a, base + "_a.png");
  writeImage(b, base + "_b.png");
  ++serial;
}

inline SetDifference compareViews(const CaptureSink& a, const CaptureSink& b) {
  SetDifference d;
  EXPECT_EQ(a.views.size(), b.views.size());
  for (const auto& [key, img] : a.views) {
    ImageDifference x = compareImages(img, b.views.at(key));
    if (x.identicalFraction < 1.0) dumpPair(img, b.views.at(key), key.second);
    d.minPsnr = std::min(d.minPsnr, x.psnr);
    d.minIdentical = std::min(d.minIdentical, x.identicalFraction);
    d.minClose = std::min(d.minClose, x.closeFraction);
  }
  return d;
}

// One scene in every back end, each against svr: "svr-layered",
// "deferred" and the MVR modes by name ("cpu", "exact", "strip", "quad");
// passes holds each MVR run's "passes" note.
struct BackEndsAgainstSvr {
  std::map<std::string, SetDifference> difference;
  std::map<std::string, std::string> passes;
};

inline BackEndsAgainstSvr compareBackEndsWithSvr(const Scene& scene, const ShearingCamera& cam) {
  BackEndsAgainstSvr out;
  auto svr = makeSvrRenderer(scene, PixelType::U8);
  const CaptureSink reference = renderViews(*svr, cam);
  auto layered = makeLayeredSvrRenderer(scene, PixelType::U8, /*forceLayers=*/true);
  out.difference["svr-layered"] = compareViews(reference, renderViews(*layered, cam));
  auto deferred = makeDeferredRenderer(scene, PixelType::U8);
  out.difference["deferred"] = compareViews(reference, renderViews(*deferred, cam));
  for (PstMode mode : {PstMode::Cpu, PstMode::Exact, PstMode::Strip, PstMode::Quad}) {
    auto mvr = makeMvrRenderer(scene, mode, PixelType::U8);
    RenderStats stats;
    out.difference[pstModeName(mode)] = compareViews(reference, renderViews(*mvr, cam, stats));
    out.passes[pstModeName(mode)] = stats.notes["passes"];
  }
  return out;
}

}  // namespace mvr::test
