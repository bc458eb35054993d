#pragma once
// Progress for long work, on stderr only: a live line on a terminal, a line
// per tenth otherwise; nothing during the first second, so short jobs stay
// quiet. Counted in the unit the user asked for (views), with the rate and
// the time left, whatever order the back end renders in.
#include <optional>
#include <string>
#include <vector>

#include "mvr/renderer.h"
#include "mvr/timer.h"

namespace mvr {

class Progress {
 public:
  // total steps of work that render `views` views, begun at `since`;
  // label names the work.
  Progress(std::string label, long total, long views, const Stopwatch& since = Stopwatch());
  ~Progress();
  void step(long n = 1);

 private:
  std::string label_;
  long total_, views_, done_ = 0;
  int lastTenth_ = 0;
  bool tty_;
  bool printed_ = false;
  Stopwatch clock_;
};

// Counts the frames a renderer hands on (views, or EPIs of every view)
// against the rendered camera's total and reports them as a share of the
// set's views.
class ProgressSink final : public FrameSink {
 public:
  // rendered: the camera the renderer draws (more views and pixels when
  // supersampled); views: the views the set will hold.
  ProgressSink(FrameSink& inner, const ShearingCamera& rendered, long views, std::string label);
  // The same over several renders into this sink (a split job's shares).
  ProgressSink(FrameSink& inner, const std::vector<ShearingCamera>& renders, long views, std::string label);
  void putView(int row, int view, const Image& image) override;
  void putEpi(int row, int scanline, const Image& epi) override;
  void putEpiInPlace(int row, int scanline, Image& epi) override;
  void finish() override;

 private:
  void stepEpi();
  FrameSink& inner_;
  long viewFrames_, epiFrames_, views_;
  std::string label_;
  Stopwatch since_;  // the render's start, not its first frame's
  std::optional<Progress> progress_;
};

// "mvr: 25% of 100 views (svr), 12.5 views/s, 6.0 s left": a share of the
// work done after `seconds`, in views.
std::string progressLine(const std::string& label, double fraction, long views, double seconds);

// Turned off by tests and the benchmark, and by MVR_PROGRESS=0.
void setProgressEnabled(bool enabled);

}  // namespace mvr
