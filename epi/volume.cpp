#include "epi/volume.h"

#include <cstring>

#include "mvr/error.h"

namespace mvr {

EpisToViews::EpisToViews(FrameSink& inner, int width, int height, int views, PixelType type)
    : inner_(inner), height_(height), views_(views), frames_(views, Image(width, height, type)) {}

void EpisToViews::putEpi(int row, int scanline, const Image& epi) {
  if (epi.height != views_ || scanline < 0 || scanline >= height_) fail("EPI sink", "EPI of the wrong shape");
  if (received_ == 0) row_ = row;
  for (int i = 0; i < views_; ++i)
    std::memcpy(frames_[i].row(scanline), epi.row(i), epi.rowBytes());
  if (++received_ < height_) return;
  for (int i = 0; i < views_; ++i) inner_.putView(row_, i, frames_[i]);
  received_ = 0;
}

ViewsToEpis::ViewsToEpis(FrameSink& inner, int width, int height, int views, PixelType type)
    : inner_(inner), width_(width), height_(height), views_(views), type_(type),
      views_held_(views) {}

void ViewsToEpis::putView(int row, int view, const Image& image) {
  views_held_[view] = image;
  if (++received_ < views_) return;
  Image epi(width_, views_, type_);
  for (int j = 0; j < height_; ++j) {
    for (int i = 0; i < views_; ++i)
      std::memcpy(epi.row(i), views_held_[i].row(j), epi.rowBytes());
    inner_.putEpi(row, j, epi);
  }
  received_ = 0;
}

}  // namespace mvr
