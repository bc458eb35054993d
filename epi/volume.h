#pragma once
// Reordering between EPI-major and view-major frames (a sink concern, not a
// renderer's): view i's scanline j is EPI j's row i.
#include <vector>

#include "mvr/renderer.h"

namespace mvr {

// Collects the EPIs of one row of views and hands the views on once all
// scanlines have arrived. Holds one row's volume: W x H x N pixels.
class EpisToViews final : public FrameSink {
 public:
  EpisToViews(FrameSink& inner, int width, int height, int views, PixelType type);
  void putEpi(int row, int scanline, const Image& epi) override;
  void finish() override { inner_.finish(); }

 private:
  FrameSink& inner_;
  int height_, views_;
  std::vector<Image> frames_;  // the row's views, filled scanline by scanline
  int received_ = 0;
  int row_ = 0;
};

// Collects all views of one row, then hands on its EPIs.
class ViewsToEpis final : public FrameSink {
 public:
  ViewsToEpis(FrameSink& inner, int width, int height, int views, PixelType type);
  void putView(int row, int view, const Image& image) override;
  void finish() override { inner_.finish(); }

 private:
  FrameSink& inner_;
  int width_, height_, views_;
  PixelType type_;
  std::vector<Image> views_held_;
  int received_ = 0;
};

}  // namespace mvr
