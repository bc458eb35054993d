#pragma once
// The GPU's own time per stage, from timestamp queries: wall-clock stages
// show where the CPU waits, not what the GPU spends its time on. Off
// unless enabled (the bench's --gpu-times); then a renderer marks where
// each stage's commands begin, and whoever timed the render collects the
// intervals between marks once the render has drained.
#include <string>
#include <vector>

#include "mvr/timer.h"

namespace mvr::gl {

class GpuClock {
 public:
  static void enable(bool on);
  static bool enabled();

  // The GPU commands issued from here to the next mark belong to `stage`.
  static void mark(const char* stage);
  // Ends the last stage and adds each stage's GPU seconds to `times` as
  // "gpu:<stage>" (waits for the queries: call it after timing).
  static void collect(StageTimes& times);
  // Forgets the marks of a render nobody collected (a warm-up).
  static void discard();

 private:
  struct Mark {
    unsigned query;
    std::string stage;
  };
  static std::vector<Mark>& marks();
};

}  // namespace mvr::gl
