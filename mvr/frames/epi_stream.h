#pragma once
// The raw EPI-major stream: EPIs written as they complete, so a display
// process can consume them while rendering goes on and memory stays at one
// EPI. Format (all integers little-endian uint32), docs/EPI_STREAM.md:
//
//   header, 64 bytes: "MVREPI01", header_bytes (64 or 144), width, height
//                     (scanlines), views, rows, channels (4: RGBA),
//                     bytes_per_channel (1: uint8, 4: float32),
//                     color_encoding, frames (0 in older streams: 1),
//                     4 zero bytes, start time and frame rate (float64;
//                     a still's 0, 0); with 144, the camera follows as
//                     ten little-endian float64 values
//   then per frame, per row of views, per scanline in order:
//                     row, scanline, then views x width x channels values:
//                     EPI row i is view i's scanline, left to right.
#include <cstdint>
#include <functional>
#include <istream>
#include <optional>
#include <ostream>
#include <span>
#include <vector>

#include "mvr/camera.h"
#include "mvr/renderer.h"

namespace mvr {

// The camera a stream was rendered with, so a consumer can write the same
// manifest (per-view cameras) the producer would have.
struct StreamCamera {
  CameraSpec spec;           // plane height resolved, never 0
  double imagePlaneZ = 0.0;  // where the rig's image plane sits in the scene (--focal)
};

struct EpiStreamHeader {
  uint32_t width = 0, height = 0, views = 0, rows = 1, channels = 4, bytesPerChannel = 1;
  // 1: 8-bit colour is sRGB-encoded (Srgb8); 0: linear. Floats are linear.
  uint32_t srgb = 0;
  // A sequence's frames (mvr render --frames), each a whole set of EPIs,
  // frame k at startTime + k / frameRate seconds; a still is 1 frame.
  uint32_t frames = 1;
  double startTime = 0.0, frameRate = 0.0;
  std::optional<StreamCamera> camera;  // absent in 64-byte headers
  PixelType pixelType() const {
    return bytesPerChannel == 4 ? PixelType::F32 : srgb ? PixelType::Srgb8 : PixelType::U8;
  }
  size_t epiBytes() const { return size_t(width) * views * channels * bytesPerChannel; }
  // The layout: the header, then one record (an 8-byte tag and the EPI)
  // per frame, row and scanline in order, so a record's place is known
  // before it is rendered (a stream split over ranks writes records at
  // their offsets).
  size_t headerBytes() const;
  size_t recordBytes() const { return 8 + epiBytes(); }
  uint64_t episPerFrame() const { return uint64_t(height) * rows; }
  uint64_t recordOffset(int row, int scanline, int frame = 0) const {
    return headerBytes() +
           (uint64_t(frame) * episPerFrame() + uint64_t(row) * height + uint64_t(scanline)) * recordBytes();
  }
  // The header's bytes as written.
  std::vector<uint8_t> encode() const;
};

// Records at their offsets through `write` (a file every rank of a split
// job shares): the stream's bytes whatever order EPIs arrive in. The
// header is written by whoever owns offset 0.
class EpiRecordSink final : public FrameSink {
 public:
  using Write = std::function<void(uint64_t offset, std::span<const std::byte> bytes)>;
  EpiRecordSink(const EpiStreamHeader& header, Write write) : header_(header), write_(std::move(write)) {}
  void putEpi(int row, int scanline, const Image& epi) override;

 private:
  EpiStreamHeader header_;
  Write write_;
};

class EpiStreamWriter final : public FrameSink {
 public:
  // Writes the header at once. `out` must outlive the writer.
  EpiStreamWriter(std::ostream& out, const EpiStreamHeader& header);
  void putEpi(int row, int scanline, const Image& epi) override;
  void finish() override;
  size_t episWritten() const { return written_; }

 private:
  std::ostream& out_;
  EpiStreamHeader header_;
  size_t written_ = 0;
};

// Reads a stream back: header first, then EPIs until the end.
class EpiStreamReader {
 public:
  // Throws on a bad header, or one beyond the renderer's Limits.
  explicit EpiStreamReader(std::istream& in);
  const EpiStreamHeader& header() const { return header_; }
  struct Frame {
    int row, scanline;
    Image epi;
    int frame = 0;  // of a sequence
  };
  // The next EPI in stream order; nullopt after the header's last one.
  // Throws on a stream cut short, an EPI tagged out of order, or data
  // after the last EPI.
  std::optional<Frame> next();
  // The same into `frame`, false after the last one: an EPI whose buffer
  // already has the stream's size is read into it, with no allocation or
  // zero-fill (a sink that takes EPIs in place leaves one there).
  bool next(Frame& frame);

 private:
  std::istream& in_;
  EpiStreamHeader header_;
  size_t read_ = 0;  // EPIs read so far
};

}  // namespace mvr
