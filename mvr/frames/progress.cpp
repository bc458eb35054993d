#include "mvr/frames/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string_view>

namespace mvr {
namespace {
// MVR_PROGRESS=0 silences it for scripts that keep stderr for errors.
bool fromEnvironment() {
  const char* v = std::getenv("MVR_PROGRESS");
  return !(v && std::string_view(v) == "0");
}
bool gEnabled = fromEnvironment();
}  // namespace

void setProgressEnabled(bool enabled) { gEnabled = enabled; }

Progress::Progress(std::string label, long total, long views, const Stopwatch& since)
    : label_(std::move(label)), total_(std::max(1L, total)), views_(views), tty_(isatty(STDERR_FILENO)),
      clock_(since) {}

Progress::~Progress() {
  if (printed_ && tty_) std::fputc('\n', stderr);
}

std::string progressLine(const std::string& label, double fraction, long views, double seconds) {
  const double rate = seconds > 0 ? fraction * double(views) / seconds : 0.0;
  const double left = fraction > 0 ? seconds * (1.0 - fraction) / fraction : 0.0;
  char text[256];
  std::snprintf(text, sizeof text, "mvr: %d%% of %ld views (%s), %.1f views/s, %.1f s left", int(100 * fraction),
                views, label.c_str(), rate, left);
  return text;
}

void Progress::step(long n) {
  done_ += n;
  const int tenth = int(10 * done_ / total_);
  if (!gEnabled || clock_.seconds() < 1.0) {
    lastTenth_ = tenth;
    return;
  }
  const std::string line = progressLine(label_, double(done_) / double(total_), views_, clock_.seconds());
  if (tty_) {
    std::fprintf(stderr, "\r%s   ", line.c_str());
    printed_ = true;
  } else if (tenth > lastTenth_) {
    std::fprintf(stderr, "%s\n", line.c_str());
  }
  lastTenth_ = tenth;
}

ProgressSink::ProgressSink(FrameSink& inner, const ShearingCamera& rendered, long views, std::string label)
    : ProgressSink(inner, std::vector{rendered}, views, std::move(label)) {}

ProgressSink::ProgressSink(FrameSink& inner, const std::vector<ShearingCamera>& renders, long views,
                           std::string label)
    : inner_(inner), viewFrames_(0), epiFrames_(0), views_(views), label_(std::move(label)) {
  // The shares' frames (a process of a split job reports its own part).
  for (const ShearingCamera& c : renders) {
    viewFrames_ += long(c.share().views.size()) * c.share().rows.size();
    epiFrames_ += long(c.share().scanlines.size()) * c.share().rows.size();
  }
}

void ProgressSink::putView(int row, int view, const Image& image) {
  inner_.putView(row, view, image);
  if (!progress_) progress_.emplace(label_, viewFrames_, views_, since_);
  progress_->step();
}

void ProgressSink::putEpi(int row, int scanline, const Image& epi) {
  inner_.putEpi(row, scanline, epi);
  stepEpi();
}

void ProgressSink::putEpiInPlace(int row, int scanline, Image& epi) {
  inner_.putEpiInPlace(row, scanline, epi);
  stepEpi();
}

void ProgressSink::stepEpi() {
  if (!progress_) progress_.emplace(label_, epiFrames_, views_, since_);
  progress_->step();
}

void ProgressSink::finish() {
  progress_.reset();  // ends a live line before what follows
  inner_.finish();
}

}  // namespace mvr
