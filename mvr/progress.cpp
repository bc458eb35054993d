#include "mvr/progress.h"

#include <unistd.h>

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

Progress::Progress(std::string label, long total)
    : label_(std::move(label)), total_(total), tty_(isatty(STDERR_FILENO)) {}

Progress::~Progress() {
  if (printed_ && tty_) std::fputc('\n', stderr);
}

void Progress::step(long n) {
  done_ += n;
  int tenth = int(10 * done_ / total_);
  if (!gEnabled || clock_.seconds() < 1.0) {
    lastTenth_ = tenth;
    return;
  }
  if (tty_) {
    std::fprintf(stderr, "\r%s: %ld/%ld", label_.c_str(), done_, total_);
    printed_ = true;
  } else if (tenth > lastTenth_) {
    std::fprintf(stderr, "%s: %d%%\n", label_.c_str(), tenth * 10);
  }
  lastTenth_ = tenth;
}

}  // namespace mvr
