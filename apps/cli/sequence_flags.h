#pragma once
// A sequence of frames from one process (issue 47): its command-line flags
// and what they resolve to. Frame k shows the scene at time
// t_k = start + k / fps; a turntable turns it by degrees * k / frames.
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

namespace mvr::app {

struct Sequence {
  int frames = 0;  // 0: a still, no sequence
  double fps = 30.0, start = 0.0;
  std::optional<double> end;  // --time A:B
  double turntable = 0.0;     // degrees over the whole sequence
  bool resume = false;        // skip the frames that are complete
  bool video = false;         // the quilts as one MP4 (mvr/images/quilt_video.h)
  int crf = 18;               // its H.264 quality: 0 lossless .. 51
  std::string clip;           // the one animation clip that plays ("": all)
  // No --frames or --time B: as many frames as the scene's animation
  // lasts, known once the scene is read (fromAnimation()).
  bool untilAnimationEnds = false;
  std::string flagWithoutLength;  // the flag that asked for it, for its error

  bool active() const { return frames > 0 || untilAnimationEnds; }
  // Frames at start + k / fps inside [start, length).
  void fromAnimation(double length);
  double timeOf(int k) const { return start + k / fps; }
  double degreesAt(int k) const { return turntable * k / frames; }
};

// Frame k's folder in a sequence's output: frame_0000, frame_0001, ...
// (mvr render --frames writes them, mvr-consume of a sequence's stream too).
std::string frameFolderName(int k);

class SequenceFlags {
 public:
  // streams: for mvr stream, whose frames go one after another into the
  // stream (no --resume, --video or --crf).
  void add(CLI::App& app, bool streams = false);
  // After parsing; throws mvr::Error naming the flag for a bad value.
  Sequence resolve() const;

 private:
  std::optional<int> frames_;
  std::optional<double> fps_, turntable_;
  std::string time_;
  bool resume_ = false, video_ = false;
  std::optional<int> crf_;
  std::string clip_;
};

}  // namespace mvr::app
