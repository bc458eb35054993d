#pragma once
// interp's source views among the views it renders: a view at a source's
// eye is that source's own image, not an interpolation.
#include <algorithm>
#include <cmath>
#include <vector>

#include "mvr/camera.h"
#include "mvr/renderer.h"
#include "mvr/views/source_layers.h"

namespace mvr {

// The layers of one source view.
struct Source {
  double x;  // camera x
  std::vector<SourceLayer> layers;
};

// A view of the set that is a source view, and that source's image: its
// nearest layer (F32, rows top first; empty where the source saw nothing).
struct SourceView {
  int view;
  Image color;
};

// Hands EPIs on with the rows of the views that are source views replaced
// by the sources' own pixels: there the best image of the scene is the
// source itself, whereas the slices of the other sources, each exact only
// at its own eye, win the depth test wherever their chords of a curved
// surface pass in front of it (de Quilletes' dual reproduced its ends only
// approximately; issue 18).
class SourceViewSink final : public FrameSink {
 public:
  SourceViewSink(FrameSink& inner, const std::vector<SourceView>& views) : inner_(inner), views_(views) {}
  void putEpi(int row, int scanline, const Image& epi) override {
    if (views_.empty()) return inner_.putEpi(row, scanline, epi);
    copy_ = epi;
    putEpiInPlace(row, scanline, copy_);
  }
  // No copy (of every EPI: 0.1 s of interp dual's 0.22 at 640x480 x 500
  // views on an H100).
  void putEpiInPlace(int row, int scanline, Image& epi) override {
    for (const SourceView& v : views_)
      for (int x = 0; x < epi.width; ++x) epi.setLinear(x, v.view, v.color.pixel(x, scanline));
    inner_.putEpi(row, scanline, epi);
  }
  void finish() override { inner_.finish(); }

 private:
  FrameSink& inner_;
  const std::vector<SourceView>& views_;
  Image copy_;
};

// The view of cam whose eye is camera x `x`, or -1.
inline int viewAt(const ShearingCamera& cam, double x) {
  const double spacing = cam.viewSpacing();
  const int i = spacing != 0.0 ? int(std::lround((x - cam.viewX(0)) / spacing)) : 0;
  return i >= 0 && i < cam.views() && std::abs(cam.viewX(i) - x) <= 1e-9 * std::max(1.0, std::abs(spacing)) ? i : -1;
}

// The views of cam that are source views, with their sources' nearest
// layers; none where the views at source eyes are not the sources' images
// (split highlights are added per view).
inline std::vector<SourceView> sourceViews(const ShearingCamera& cam, const std::vector<Source>& sources,
                                           bool passesThrough) {
  std::vector<SourceView> views;
  for (const Source& source : sources)
    if (const int v = passesThrough ? viewAt(cam, source.x) : -1; v >= 0)
      views.push_back({v, source.layers.empty() ? Image(cam.width(), cam.height(), PixelType::F32)
                                                : source.layers.front().color});
  return views;
}

}  // namespace mvr
