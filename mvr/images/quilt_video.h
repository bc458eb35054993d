#pragma once
// A sequence's quilts as one video: an MP4 of H.264 in yuv420p that
// Looking Glass players load, named by their convention
// (quilt_qs8x6a0.75.mp4). Encoded by mvr-encode (beside this program, or
// MVR_ENCODE) in a process of its own, fed frame by frame through a pipe:
// the encoding runs beside the rendering, and FFmpeg's libraries load only
// when a video is asked for. The file appears when every frame is in it.
#include <sys/types.h>

#include <string>
#include <vector>

#include "mvr/image.h"

namespace mvr {

class QuiltVideo {
 public:
  // Half: yuv420p, what players expect of a quilt. Full: yuv444p, for a
  // panel's native image, whose neighbouring subpixels show different
  // views (halved chroma would mix them).
  enum class Chroma { Half, Full };
  // Starts the encoder; throws mvr::Error naming the file.
  QuiltVideo(std::string path, int width, int height, double fps, int crf, int frames, Chroma chroma = Chroma::Half);
  ~QuiltVideo();  // unfinished: the encoder stopped, no file left
  QuiltVideo(const QuiltVideo&) = delete;
  QuiltVideo& operator=(const QuiltVideo&) = delete;

  // The next frame (the quilt, any pixel type: sRGB-encoded 8-bit on the
  // way). Blocks while the encoder is a few frames behind.
  void add(const Image& quilt);
  // Waits for the encoder; throws its one-line error.
  void finish();

 private:
  void stop();

  std::string path_;
  int width_, height_;
  pid_t pid_ = -1;
  int input_ = -1;   // the encoder's stdin
  int errors_ = -1;  // its stderr
  std::vector<uint8_t> rgba_;
};

}  // namespace mvr
