#pragma once
// Progress for long work, on stderr only: a live line on a terminal, a line
// per tenth otherwise; nothing during the first second, so short jobs stay quiet.
#include <string>

#include "mvr/timer.h"

namespace mvr {

class Progress {
 public:
  Progress(std::string label, long total);
  ~Progress();
  void step(long n = 1);

 private:
  std::string label_;
  long total_, done_ = 0;
  int lastTenth_ = 0;
  bool tty_;
  bool printed_ = false;
  Stopwatch clock_;
};

// Turned off by tests and the benchmark, and by MVR_PROGRESS=0.
void setProgressEnabled(bool enabled);

}  // namespace mvr
