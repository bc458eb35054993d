#include "mvr/frames/epi_stream.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>

#include "mvr/camera.h"
#include "mvr/error.h"

namespace mvr {
namespace {

constexpr char kMagic[8] = {'M', 'V', 'R', 'E', 'P', 'I', '0', '1'};
constexpr uint32_t kHeaderBytes = 64;
constexpr int kMaxFrames = 1 << 20;
// The camera block after the fixed header: distance, plane width and
// height, track left and right, row top and bottom, near, far, image plane z.
constexpr uint32_t kCameraValues = 10;
constexpr uint32_t kHeaderWithCameraBytes = kHeaderBytes + 8 * kCameraValues;

void putU32(uint8_t* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = uint8_t(v >> (8 * i));
}
uint32_t getU32(const uint8_t* p) {
  return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}
void putF64(uint8_t* p, double v) {
  uint64_t bits = 0;
  std::memcpy(&bits, &v, 8);
  for (int i = 0; i < 8; ++i) p[i] = uint8_t(bits >> (8 * i));
}
double getF64(const uint8_t* p) {
  uint64_t bits = 0;
  for (int i = 0; i < 8; ++i) bits |= uint64_t(p[i]) << (8 * i);
  double v = 0;
  std::memcpy(&v, &bits, 8);
  return v;
}

std::array<double, kCameraValues> cameraValues(const StreamCamera& c) {
  const CameraSpec& s = c.spec;
  return {s.distance, s.planeWidth, s.planeHeight, s.trackLeft, s.trackRight,
          s.rowTop,   s.rowBottom,  s.nearDistance, s.farDistance, c.imagePlaneZ};
}

StreamCamera cameraOf(const std::array<double, kCameraValues>& v) {
  for (double x : v)
    if (!std::isfinite(x)) fail("stream", "header camera holds a value that is not a finite number");
  StreamCamera c;
  c.spec = {v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8]};
  c.imagePlaneZ = v[9];
  return c;
}

}  // namespace

size_t EpiStreamHeader::headerBytes() const { return camera ? kHeaderWithCameraBytes : kHeaderBytes; }

std::vector<uint8_t> EpiStreamHeader::encode() const {
  std::vector<uint8_t> bytes(headerBytes(), 0);
  std::memcpy(bytes.data(), kMagic, 8);
  const uint32_t fields[] = {uint32_t(bytes.size()), width, height, views, rows, channels, bytesPerChannel, srgb, frames};
  for (size_t i = 0; i < std::size(fields); ++i) putU32(bytes.data() + 8 + 4 * i, fields[i]);
  putF64(bytes.data() + 48, startTime);
  putF64(bytes.data() + 56, frameRate);
  if (camera) {
    const auto values = cameraValues(*camera);
    for (uint32_t i = 0; i < kCameraValues; ++i) putF64(bytes.data() + kHeaderBytes + 8 * i, values[i]);
  }
  return bytes;
}

namespace {

// An EPI's tag, after checking it fits the header.
std::array<uint8_t, 8> recordTag(const EpiStreamHeader& header, int row, int scanline, const Image& epi) {
  if (size_t(epi.width) != header.width || size_t(epi.height) != header.views || epi.type != header.pixelType())
    fail("stream", "EPI does not match the stream header");
  std::array<uint8_t, 8> tag;
  putU32(tag.data(), uint32_t(row));
  putU32(tag.data() + 4, uint32_t(scanline));
  return tag;
}

}  // namespace

EpiStreamWriter::EpiStreamWriter(std::ostream& out, const EpiStreamHeader& h) : out_(out), header_(h) {
  const std::vector<uint8_t> bytes = h.encode();
  out_.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
  if (!out_) fail("stream", "cannot write header");
}

void EpiStreamWriter::putEpi(int row, int scanline, const Image& epi) {
  const std::array<uint8_t, 8> tag = recordTag(header_, row, scanline, epi);
  out_.write(reinterpret_cast<const char*>(tag.data()), 8);
  out_.write(reinterpret_cast<const char*>(epi.bytes.data()), std::streamsize(epi.bytes.size()));
  if (!out_) fail("stream", "write failed (consumer gone or disk full)");
  ++written_;
}

void EpiRecordSink::putEpi(int row, int scanline, const Image& epi) {
  const std::array<uint8_t, 8> tag = recordTag(header_, row, scanline, epi);
  const uint64_t at = header_.recordOffset(row, scanline);
  write_(at, std::as_bytes(std::span(tag)));
  write_(at + 8, std::as_bytes(std::span(epi.bytes)));
}

void EpiStreamWriter::finish() {
  out_.flush();
  if (!out_) fail("stream", "flush failed");
}

EpiStreamReader::EpiStreamReader(std::istream& in) : in_(in) {
  std::array<uint8_t, kHeaderBytes> bytes{};
  in_.read(reinterpret_cast<char*>(bytes.data()), bytes.size());
  if (!in_ || std::memcmp(bytes.data(), kMagic, 8) != 0) fail("stream", "not an MVREPI01 stream");
  const uint32_t size = getU32(bytes.data() + 8);
  if (size != kHeaderBytes && size != kHeaderWithCameraBytes)
    fail("stream", "unsupported header size " + std::to_string(size) + " (64 or 144)");
  header_.width = getU32(bytes.data() + 12);
  header_.height = getU32(bytes.data() + 16);
  header_.views = getU32(bytes.data() + 20);
  header_.rows = getU32(bytes.data() + 24);
  header_.channels = getU32(bytes.data() + 28);
  header_.bytesPerChannel = getU32(bytes.data() + 32);
  header_.srgb = getU32(bytes.data() + 36);
  if (header_.srgb > 1 || (header_.srgb && header_.bytesPerChannel != 1))
    fail("stream", "header color encoding " + std::to_string(header_.srgb) + " is not 0 (linear) or 1 (sRGB bytes)");
  if (header_.channels != 4 || (header_.bytesPerChannel != 1 && header_.bytesPerChannel != 4) ||
      header_.width == 0 || header_.views == 0 || header_.height == 0 || header_.rows == 0)
    fail("stream", "header describes no valid EPI");
  // The renderer's own bounds (mvr/camera.h): a header beyond them is not
  // from mvr, and sizing buffers from it could exhaust memory.
  auto within = [](const char* field, uint32_t value, int limit) {
    if (value > uint32_t(limit))
      fail("stream", std::string("header ") + field + " " + std::to_string(value) + " exceeds " +
                         std::to_string(limit));
  };
  within("width", header_.width, Limits::kMaxSide);
  within("height", header_.height, Limits::kMaxSide);
  within("views", header_.views, Limits::kMaxViews);
  within("rows", header_.rows, Limits::kMaxRows);
  header_.frames = std::max<uint32_t>(getU32(bytes.data() + 40), 1);
  within("frames", header_.frames, kMaxFrames);
  header_.startTime = getF64(bytes.data() + 48);
  header_.frameRate = getF64(bytes.data() + 56);
  if (!std::isfinite(header_.startTime) || !std::isfinite(header_.frameRate) || header_.frameRate < 0.0)
    fail("stream", "header start time or frame rate is not a finite time (a rate at least 0)");
  if (size == kHeaderWithCameraBytes) {
    std::array<uint8_t, 8 * kCameraValues> block{};
    in_.read(reinterpret_cast<char*>(block.data()), block.size());
    if (size_t(in_.gcount()) != block.size()) fail("stream", "truncated header camera");
    std::array<double, kCameraValues> values{};
    for (uint32_t i = 0; i < kCameraValues; ++i) values[i] = getF64(block.data() + 8 * i);
    header_.camera = cameraOf(values);
  }
}

std::optional<EpiStreamReader::Frame> EpiStreamReader::next() {
  std::optional<Frame> f(Frame{});
  if (!next(*f)) return std::nullopt;
  return f;
}

bool EpiStreamReader::next(Frame& f) {
  const size_t perFrame = header_.episPerFrame(), total = perFrame * header_.frames;
  uint8_t tag[8];
  in_.read(reinterpret_cast<char*>(tag), 8);
  if (read_ == total) {  // complete: anything more is not this stream
    if (in_.gcount() == 0 && in_.eof()) return false;
    fail("stream", "data after the last of " + std::to_string(total) + " EPIs");
  }
  if (in_.gcount() == 0 && in_.eof())
    fail("stream", "ended after " + std::to_string(read_) + " of " + std::to_string(total) + " EPIs");
  if (in_.gcount() != 8) fail("stream", "truncated EPI tag");
  // EPI-major order: frame by frame, row by row, scanline by scanline.
  const size_t inFrame = read_ % perFrame;
  const uint32_t row = uint32_t(inFrame / header_.height), scanline = uint32_t(inFrame % header_.height);
  f.frame = int(read_ / perFrame);
  if (getU32(tag) != row || getU32(tag + 4) != scanline)
    fail("stream", "EPI " + std::to_string(read_) + " is tagged row " + std::to_string(getU32(tag)) +
                       " scanline " + std::to_string(getU32(tag + 4)) + ", expected row " +
                       std::to_string(row) + " scanline " + std::to_string(scanline));
  ++read_;
  f.row = int(getU32(tag));
  f.scanline = int(getU32(tag + 4));
  f.epi.width = int(header_.width);
  f.epi.height = int(header_.views);
  f.epi.type = header_.pixelType();
  // In pieces, the buffer growing with the data that arrived: a hostile
  // header promising gigabytes must not allocate them before the stream
  // shows it has them. A buffer of the right size is read into whole.
  constexpr size_t kPiece = size_t(16) << 20;
  const size_t bytes = header_.epiBytes();
  const bool reuse = f.epi.bytes.size() == bytes;
  if (!reuse) f.epi.bytes.clear();
  for (size_t have = 0; have < bytes;) {
    const size_t piece = reuse ? bytes : std::min(kPiece, bytes - have);
    if (!reuse) f.epi.bytes.resize(have + piece);
    in_.read(reinterpret_cast<char*>(f.epi.bytes.data() + have), std::streamsize(piece));
    if (size_t(in_.gcount()) != piece) fail("stream", "truncated EPI data");
    have += piece;
  }
  return true;
}

}  // namespace mvr
