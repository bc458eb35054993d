#pragma once
// Per-stage wall-clock timing, reported in manifests and by the benchmark.
#include <chrono>
#include <map>
#include <string>

namespace mvr {

struct StageTimes {
  std::map<std::string, double> seconds;
  void add(const std::string& stage, double s) { seconds[stage] += s; }
  double total() const {
    double t = 0;
    for (const auto& [k, v] : seconds) t += v;
    return t;
  }
};

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  double restart() {
    double s = seconds();
    start_ = std::chrono::steady_clock::now();
    return s;
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

// Adds the scope's duration to one stage.
class ScopedStage {
 public:
  ScopedStage(StageTimes& times, std::string stage) : times_(times), stage_(std::move(stage)) {}
  ~ScopedStage() { times_.add(stage_, watch_.seconds()); }

 private:
  StageTimes& times_;
  std::string stage_;
  Stopwatch watch_;
};

}  // namespace mvr
