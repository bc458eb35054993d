#include "apps/cli/sequence_flags.h"

#include <cmath>
#include <cstdio>

#include "mvr/error.h"

namespace mvr::app {

std::string frameFolderName(int k) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d", k);
  return name;
}

void SequenceFlags::add(CLI::App& app, bool streams) {
  app.add_option("--frames", frames_,
                 streams ? "stream a sequence of N frames, one whole set of EPIs after another, the header "
                           "saying how many and at what times (docs/EPI_STREAM.md); without it, a sequence "
                           "flag streams the scene's animation to its end"
                         : "render a sequence of N frames, each a complete set in frame_0000/, frame_0001/, ... "
                           "(views, quilt, depth maps as asked, its manifest with its time), listed in "
                           "sequence.json; without it, a sequence flag renders the scene's animation to its end")
      ->type_name("N");
  app.add_option("--fps", fps_, "frames per second of the sequence's time (default 30)")->type_name("F");
  app.add_option("--time", time_,
                 "the sequence's time: frame k at A + k / fps; with B and without --frames, enough frames "
                 "to cover [A, B)")
      ->type_name("A[:B]");
  app.add_option("--turntable", turntable_,
                 "turn the scene about the vertical axis through the centre of its bounds by DEG over the "
                 "sequence (frame k: DEG k / N; 360 loops without a repeated frame); positive turns +x "
                 "toward -z; lights and camera stay")
      ->type_name("DEG");
  app.add_option("--clip", clip_, "play only the scene's animation clip of this name (default: every clip together)")
      ->type_name("NAME");
  if (streams) return;  // what follows concerns frame folders
  app.add_flag("--resume", resume_, "keep the frames of an earlier run of this sequence that are complete");
  app.add_flag("--video", video_,
               "with --quilt: also write the quilts as one video, quilt_qs{C}x{R}a{aspect}.mp4 (H.264 in "
               "yuv420p, as Looking Glass players load), encoded while the frames render");
  app.add_option("--crf", crf_, "the video's quality: 0 (lossless) to 51 (worst); default 18, visually lossless")
      ->type_name("Q");
}

namespace {

double number(const std::string& text, const char* flag) {
  size_t used = 0;
  double v = 0.0;
  try {
    v = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || !std::isfinite(v)) fail(flag, "'" + text + "' is not a number");
  return v;
}

}  // namespace

Sequence SequenceFlags::resolve() const {
  Sequence s;
  s.resume = resume_;
  s.video = video_;
  if (crf_) {
    if (*crf_ < 0 || *crf_ > 51) fail("--crf", "must be 0 to 51");
    if (!video_) fail("--crf", "sets the quality of --video");
    s.crf = *crf_;
  }
  if (fps_) {
    if (!(*fps_ > 0.0 && std::isfinite(*fps_))) fail("--fps", "must be a positive number of frames per second");
    s.fps = *fps_;
  }
  if (!time_.empty()) {
    const size_t colon = time_.find(':');
    s.start = number(time_.substr(0, colon), "--time");
    if (colon != std::string::npos) {
      s.end = number(time_.substr(colon + 1), "--time");
      if (!(*s.end > s.start)) fail("--time", "the end B must come after the start A");
    }
  }
  if (turntable_) {
    if (!std::isfinite(*turntable_)) fail("--turntable", "must be a finite angle in degrees");
    s.turntable = *turntable_;
  }
  if (frames_) {
    if (*frames_ < 1 || *frames_ > 1000000) fail("--frames", "must be 1 to 1000000");
    s.frames = *frames_;
  } else if (s.end) {
    // Frames at A + k / fps inside [A, B).
    s.frames = std::max(1, int(std::ceil((*s.end - s.start) * s.fps - 1e-9)));
    if ((*s.end - s.start) * s.fps > 1e6) fail("--time", "more than 1000000 frames at this --fps");
  } else if (turntable_ || fps_ || !time_.empty() || resume_ || video_ || !clip_.empty()) {
    s.untilAnimationEnds = true;  // checked once the scene is read
    s.flagWithoutLength = turntable_ ? "--turntable" : fps_ ? "--fps" : resume_ ? "--resume" : video_ ? "--video"
                          : !clip_.empty() ? "--clip" : "--time";
  }
  s.clip = clip_;
  return s;
}

void Sequence::fromAnimation(double length) {
  if (!untilAnimationEnds) return;
  if (!(length > start))
    fail(flagWithoutLength, length > 0.0 ? "the scene's animation ends before --time's start"
                                         : "needs a sequence: --frames N or --time A:B (the scene has no animation)");
  frames = std::max(1, int(std::ceil((length - start) * fps - 1e-9)));
  untilAnimationEnds = false;
}

}  // namespace mvr::app
