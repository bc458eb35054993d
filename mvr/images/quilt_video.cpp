#include "mvr/images/quilt_video.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "mvr/color.h"
#include "mvr/error.h"
#include "mvr/files/helper_program.h"

namespace mvr {
namespace {

namespace fs = std::filesystem;

std::string readAll(int fd) {
  std::string s;
  char buffer[4096];
  for (ssize_t n; (n = read(fd, buffer, sizeof buffer)) != 0;) {
    if (n < 0) {
      if (errno == EINTR) continue;
      break;
    }
    s.append(buffer, size_t(n));
  }
  return s;
}

}  // namespace

QuiltVideo::QuiltVideo(std::string path, int width, int height, double fps, int crf, int frames, Chroma chroma)
    : path_(std::move(path)), width_(width), height_(height), rgba_(size_t(width) * height * 4) {
  const std::string helper = helperProgram("mvr-encode", "MVR_ENCODE", path_, "videos are encoded");
  const HelperProcess child =
      spawnHelper({helper, path_, std::to_string(width), std::to_string(height), std::to_string(fps),
                   std::to_string(crf), std::to_string(frames), chroma == Chroma::Full ? "yuv444p" : "yuv420p"},
                  HelperPipe::Stdin, path_);
  pid_ = child.pid, input_ = child.stream, errors_ = child.errors;
  // A vanished encoder is an error from write(), not a kill.
  signal(SIGPIPE, SIG_IGN);
}

QuiltVideo::~QuiltVideo() { stop(); }

void QuiltVideo::stop() {
  if (input_ >= 0) close(input_);
  if (pid_ > 0) {
    kill(pid_, SIGKILL);
    waitHelper(pid_);
    std::error_code ec;
    fs::remove(path_ + ".part", ec);
  }
  if (errors_ >= 0) close(errors_);
  input_ = errors_ = -1, pid_ = -1;
}

void QuiltVideo::add(const Image& quilt) {
  if (quilt.width != width_ || quilt.height != height_) fail(path_, "a quilt of another size");
  if (input_ < 0) fail(path_, "the video is finished");
  // sRGB-encoded 8-bit RGBA, as the quilt's PNG holds it.
  const size_t n = size_t(width_) * height_;
  if (quilt.type == PixelType::F32) {
    const Srgb8Encoder encode;
    const float* f = reinterpret_cast<const float*>(quilt.bytes.data());
    for (size_t i = 0; i < 4 * n; ++i) rgba_[i] = i % 4 == 3 ? uint8_t(std::lrint(std::clamp(f[i], 0.0f, 1.0f) * 255)) : encode(f[i]);
  } else {
    std::memcpy(rgba_.data(), quilt.bytes.data(), 4 * n);
  }
  const uint8_t* p = rgba_.data();
  for (size_t left = rgba_.size(); left > 0;) {
    const ssize_t put = write(input_, p, left);
    if (put < 0 && errno == EINTR) continue;
    if (put <= 0) {
      finish();  // the encoder's own message
      fail(path_, "the encoder stopped taking frames");
    }
    p += put, left -= size_t(put);
  }
}

void QuiltVideo::finish() {
  if (pid_ < 0) return;
  close(input_);
  input_ = -1;
  const std::string err = readAll(errors_);
  const int status = waitHelper(pid_);
  pid_ = -1;
  close(errors_);
  errors_ = -1;
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    std::error_code ec;
    fs::remove(path_ + ".part", ec);
    std::string line = err.substr(0, err.find('\n'));
    if (line.rfind("mvr-encode: ", 0) == 0) line = line.substr(12);
    fail(path_, line.empty() ? "the encoder failed" : line);
  }
}

}  // namespace mvr
