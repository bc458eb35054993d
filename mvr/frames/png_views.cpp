#include "mvr/frames/png_views.h"

#include <algorithm>
#include <string>

#include "mvr/error.h"
#include "mvr/files/atomic_file.h"
#include "mvr/parallel.h"

namespace mvr {

bool EpisToPngViews::handles(const Manifest& manifest, PixelType type) {
  return manifest.format == "png" && (type == PixelType::F32 || (manifest.bits == 8 && isByteType(type)));
}

namespace {

// As writeImage writes a view: a byte image as stored, tagged by its type;
// a float one in the set's bits, sRGB-encoded where the set says sRGB.
PngFormat formatOf(const Manifest& m, PixelType type) {
  const bool bytes = isByteType(type);
  return {.width = m.width, .height = m.height, .bits = bytes ? 8 : m.bits, .level = m.compression,
          .srgb = bytes ? type == PixelType::Srgb8 : m.srgb};
}

size_t epiBytes(const Manifest& m, PixelType type) {
  return size_t(m.width) * size_t(m.views) * 4 * Image::channelBytes(type);
}

}  // namespace

int EpisToPngViews::queueLength(const Manifest& manifest, PixelType type, size_t budget) {
  const size_t bytes = std::min(size_t(128) << 20, budget / 8);
  return int(std::clamp<size_t>(bytes / std::max<size_t>(epiBytes(manifest, type), 1), 4, 64));
}

size_t EpisToPngViews::filesBudget(const Manifest& manifest, PixelType type, size_t budget) {
  const size_t views = size_t(manifest.views);
  // The queue, an EPI being fed and one held back early.
  const size_t queue = size_t(queueLength(manifest, type, budget) + 2) * epiBytes(manifest, type);
  const size_t encoders = views * PngEncoder::heldBytes(formatOf(manifest, type)) + queue;
  // Less room than this makes for many small appends to every file.
  const size_t least = views * (size_t(16) << 10);
  return budget > encoders + least ? budget - encoders : 0;
}

EpisToPngViews::EpisToPngViews(ImageSetWriter& writer, PixelType type, size_t filesBudget, int queueLength)
    : writer_(writer), type_(type), views_(writer.manifest().views), filesBudget_(filesBudget),
      queueLength_(std::max(1, queueLength)) {
  const Manifest& m = writer.manifest();
  if (!handles(m, type)) fail("PNG view sink", "needs byte images and 8-bit PNG files, or float images");
  format_ = formatOf(m, type);
  files_.resize(size_t(views_));
  spilled_.assign(size_t(views_), 0);
  encoders_.resize(size_t(views_));
}

EpisToPngViews::~EpisToPngViews() {
  {
    std::lock_guard lock(mutex_);
    queued_.clear();  // an unfinished job: what is left need not be encoded
  }
  lane_->wait();
  for (int i = 0; i < views_; ++i)
    if (spilled_[size_t(i)]) removePart(writer_.pathOf(writer_.manifest().viewName(row_, i)));
}

void EpisToPngViews::startRow(int row) {
  settle();  // the encoders of the row before are done
  row_ = row;
  next_ = 0;
  fed_ = 0;
  for (int i = 0; i < views_; ++i) encoders_[size_t(i)] = std::make_unique<PngEncoder>(format_, files_[size_t(i)]);
}

// Row `fed_` of every view, on the pool in runs of views; the files
// finished by it go to the writer, which writes them on its pool.
void EpisToPngViews::feed(const Image& epi) {
  const int run = std::max(1, views_ / (8 * threadCount()));
  const bool encode = type_ == PixelType::F32 && format_.srgb;
  parallelFor(0, (views_ + run - 1) / run, [&](int k) {
    thread_local std::vector<uint8_t> room;  // a float row's samples
    for (int i = k * run; i < std::min(views_, (k + 1) * run); ++i)
      encoders_[size_t(i)]->addRow(pngRow(epi, i, format_.bits, encode, room));
  });
  if (++fed_ < format_.height) {
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
  put(row, scanline, epi, nullptr);  // copied
}

void EpisToPngViews::putEpiInPlace(int row, int scanline, Image& epi) { put(row, scanline, epi, &epi); }

// taken: the EPI itself where its pixels may be taken, else null.
void EpisToPngViews::put(int row, int scanline, const Image& epi, Image* taken) {
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
  enqueue(epi, taken);
  for (auto it = early_.find(next_); it != early_.end(); it = early_.find(next_)) {
    enqueue(it->second, &it->second);
    early_.erase(it);
  }
}

// Scanline next_ into the queue (in a spare, mvr/image_pool.h), and a
// draining task started if none runs. A full queue is
// emptied first, the caller helping.
void EpisToPngViews::enqueue(const Image& epi, Image* taken) {
  bool full = false;
  {
    std::lock_guard lock(mutex_);
    if (error_) std::rethrow_exception(error_);
    full = int(queued_.size()) >= queueLength_;
  }
  if (full) settle();
  Image held = spares_.hold(epi, taken);
  ++next_;
  std::lock_guard lock(mutex_);
  queued_.push_back(std::move(held));
  if (!draining_) {
    draining_ = true;
    lane_->run([this] { drain(); });
  }
}

// Feeds the queued EPIs in order until none is left; the first error
// empties the queue and is kept for the producer.
void EpisToPngViews::drain() {
  for (;;) {
    Image epi;
    {
      std::lock_guard lock(mutex_);
      if (queued_.empty() || error_) {
        queued_.clear();
        draining_ = false;
        return;
      }
      epi = std::move(queued_.front());
      queued_.pop_front();
    }
    try {
      feed(epi);
    } catch (...) {
      std::lock_guard lock(mutex_);
      error_ = std::current_exception();
    }
    spares_.giveBack(std::move(epi));
  }
}

// Returns once every queued EPI is fed, helping; rethrows an encoding error.
void EpisToPngViews::settle() {
  lane_->wait();
  std::lock_guard lock(mutex_);
  if (error_) std::rethrow_exception(error_);
}

void EpisToPngViews::finish() {
  settle();
  if (row_ >= 0 && next_ < format_.height)
    fail("PNG view sink", "row " + std::to_string(row_) + " ended with " + std::to_string(format_.height - next_) +
                              " scanlines missing");
  writer_.finish();
}

}  // namespace mvr
