#include "mvr/io/png_views.h"

#include <algorithm>
#include <string>

#include "mvr/error.h"
#include "mvr/io/atomic_file.h"
#include "mvr/parallel.h"

namespace mvr {

bool EpisToPngViews::handles(const Manifest& manifest, PixelType type) {
  return manifest.format == "png" && manifest.bits == 8 && isByteType(type);
}

namespace {

PngFormat formatOf(const Manifest& m, PixelType type) {
  // As writeImage writes a byte image: as stored, tagged by its type.
  return {.width = m.width, .height = m.height, .bits = 8, .level = m.compression, .srgb = type == PixelType::Srgb8};
}

}  // namespace

size_t EpisToPngViews::filesBudget(const Manifest& manifest, size_t budget) {
  const size_t views = size_t(manifest.views);
  const size_t encoders = views * PngEncoder::heldBytes(formatOf(manifest, PixelType::U8));
  // Less room than this makes for many small appends to every file.
  const size_t least = views * (size_t(16) << 10);
  return budget > encoders + least ? budget - encoders : 0;
}

EpisToPngViews::EpisToPngViews(ImageSetWriter& writer, PixelType type, size_t filesBudget)
    : writer_(writer), type_(type), views_(writer.manifest().views), filesBudget_(filesBudget) {
  const Manifest& m = writer.manifest();
  if (!handles(m, type)) fail("PNG view sink", "needs byte images and 8-bit PNG files");
  format_ = formatOf(m, type);
  files_.resize(size_t(views_));
  spilled_.assign(size_t(views_), 0);
  encoders_.resize(size_t(views_));
}

EpisToPngViews::~EpisToPngViews() {
  for (int i = 0; i < views_; ++i)
    if (spilled_[size_t(i)]) removePart(writer_.pathOf(writer_.manifest().viewName(row_, i)));
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
  if (++next_ < format_.height) {
    size_t held = 0;
    for (const auto& file : files_) held += file.size();
    if (held > filesBudget_) spill();
    return;
  }
  for (int i = 0; i < views_; ++i) {
    encoders_[size_t(i)].reset();
    writer_.putEncoded(writer_.manifest().viewName(row_, i), std::move(files_[size_t(i)]), spilled_[size_t(i)]);
    files_[size_t(i)] = {};
    spilled_[size_t(i)] = 0;
  }
}

// Every view's bytes so far onto the end of its temporary file, on the
// pool; the encoders go on writing into the emptied vectors.
void EpisToPngViews::spill() {
  parallelFor(0, views_, [&](int i) {
    std::vector<unsigned char>& file = files_[size_t(i)];
    appendToPart(writer_.pathOf(writer_.manifest().viewName(row_, i)), std::as_bytes(std::span(file)),
                 !spilled_[size_t(i)]);
    spilled_[size_t(i)] = 1;
    std::vector<unsigned char>().swap(file);  // its memory back, not just its size
  });
  ++spills_;
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
