#pragma once
// Progress for long work, on stderr only: a live line on a terminal, a line
// per tenth otherwise, nothing for short jobs.
#include <string>

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
};

// Turned off by tests and the benchmark.
void setProgressEnabled(bool enabled);

}  // namespace mvr
