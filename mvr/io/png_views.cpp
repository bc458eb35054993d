#include "mvr/io/png_views.h"

#include <algorithm>
#include <string>

#include "mvr/error.h"
#include "mvr/parallel.h"

namespace mvr {

bool EpisToPngViews::handles(const Manifest& manifest, PixelType type) {
  return manifest.format == "png" && manifest.bits == 8 && isByteType(type);
}

EpisToPngViews::EpisToPngViews(ImageSetWriter& writer, PixelType type)
    : writer_(writer), type_(type), views_(writer.manifest().views) {
  const Manifest& m = writer.manifest();
  if (!handles(m, type)) fail("PNG view sink", "needs byte images and 8-bit PNG files");
  // As writeImage writes a byte image: as stored, tagged by its type.
  format_ = {.width = m.width, .height = m.height, .bits = 8, .level = m.compression,
             .srgb = type == PixelType::Srgb8};
  files_.resize(size_t(views_));
  encoders_.resize(size_t(views_));
}

void EpisToPngViews::startRow(int row) {
  row_ = row;
  next_ = 0;
  for (int i = 0; i < views_; ++i) encoders_[size_t(i)] = std::make_unique<PngEncoder>(format_, files_[size_t(i)]);
}

// Row `next_` of every view, on the pool in runs of views; the files
// finished by it go to the writer, which writes them on its pool.
void EpisToPngViews::feed(const Image& epi) {
  const int run = std::max(1, views_ / (8 * threadCount()));
  parallelFor(0, (views_ + run - 1) / run, [&](int k) {
    for (int i = k * run; i < std::min(views_, (k + 1) * run); ++i)
      encoders_[size_t(i)]->addRow({epi.row(i), epi.rowBytes()});
  });
  if (++next_ < format_.height) return;
  for (int i = 0; i < views_; ++i) {
    encoders_[size_t(i)].reset();
    writer_.putEncoded(writer_.manifest().viewName(row_, i), std::move(files_[size_t(i)]));
  }
}

void EpisToPngViews::putEpi(int row, int scanline, const Image& epi) {
  if (epi.width != format_.width || epi.height != views_ || epi.type != type_ || scanline < 0 ||
      scanline >= format_.height)
    fail("PNG view sink", "EPI of the wrong shape");
  if (row != row_) {
    if (row_ >= 0 && next_ < format_.height)
      fail("PNG view sink", "EPIs of row " + std::to_string(row) + " before row " + std::to_string(row_) + " was done");
    startRow(row);
  }
  if (scanline < next_ || early_.count(scanline)) fail("PNG view sink", "scanline " + std::to_string(scanline) + " twice");
  if (scanline != next_) {
    early_.emplace(scanline, epi);
    return;
  }
  feed(epi);
  for (auto it = early_.find(next_); it != early_.end(); it = early_.find(next_)) {
    feed(it->second);
    early_.erase(it);
  }
}

void EpisToPngViews::finish() {
  if (row_ >= 0 && next_ < format_.height)
    fail("PNG view sink", "row " + std::to_string(row_) + " ended with " + std::to_string(format_.height - next_) +
                              " scanlines missing");
  writer_.finish();
}

}  // namespace mvr
