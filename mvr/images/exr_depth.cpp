#include "mvr/images/exr_depth.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <string>

#include "mvr/error.h"
#include "mvr/images/adler32.h"
#include "mvr/images/row_deflate.h"

namespace mvr {
namespace {

static_assert(std::endian::native == std::endian::little, "EXR stores little-endian values, as they are held here");

// OpenEXR's values for the fields written (its file layout document).
constexpr uint32_t kMagic = 20000630, kVersion = 2;  // single-part scanline, short names
constexpr uint8_t kNoCompression = 0, kZipCompression = 3, kIncreasingY = 0;
constexpr int32_t kFloat = 2;
constexpr int kZipLines = 16;  // scanlines a ZIP chunk holds; 1 uncompressed

template <class T>
void put(std::vector<unsigned char>& out, T value) {
  unsigned char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  out.insert(out.end(), bytes, bytes + sizeof(T));
}

// An attribute: name, type name, size, value.
void attribute(std::vector<unsigned char>& out, const char* name, const char* type,
               const std::vector<unsigned char>& value) {
  out.insert(out.end(), name, name + std::strlen(name) + 1);
  out.insert(out.end(), type, type + std::strlen(type) + 1);
  put(out, int32_t(value.size()));
  out.insert(out.end(), value.begin(), value.end());
}

template <class... T>
std::vector<unsigned char> values(T... v) {
  std::vector<unsigned char> out;
  (put(out, v), ...);
  return out;
}

void putHeader(std::vector<unsigned char>& out, int w, int h, bool zip) {
  put(out, kMagic);
  put(out, kVersion);
  // One channel "Z": FLOAT, not perceptually linear, sampled every pixel.
  std::vector<unsigned char> channels = {'Z', 0};
  for (unsigned char b : values(kFloat, uint8_t(0), uint8_t(0), uint8_t(0), uint8_t(0), int32_t(1), int32_t(1)))
    channels.push_back(b);
  channels.push_back(0);
  attribute(out, "channels", "chlist", channels);
  attribute(out, "compression", "compression", {zip ? kZipCompression : kNoCompression});
  const std::vector<unsigned char> window = values(int32_t(0), int32_t(0), int32_t(w - 1), int32_t(h - 1));
  attribute(out, "dataWindow", "box2i", window);
  attribute(out, "displayWindow", "box2i", window);
  attribute(out, "lineOrder", "lineOrder", {kIncreasingY});
  attribute(out, "pixelAspectRatio", "float", values(1.0f));
  attribute(out, "screenWindowCenter", "v2f", values(0.0f, 0.0f));
  attribute(out, "screenWindowWidth", "float", values(1.0f));
  out.push_back(0);  // the header's end
}

// ZIP's preparation of a chunk's bytes (OpenEXR's ZIP codec): the even
// bytes, then the odd ones (a float's low and high halves apart), each
// then replaced by its difference from the one before, plus 128.
void interleaveAndPredict(const unsigned char* raw, size_t n, std::vector<uint8_t>& out) {
  out.resize(n);
  const size_t half = (n + 1) / 2;
  uint8_t* even = out.data();
  uint8_t* odd = out.data() + half;
  for (size_t k = 0; k < n / 2; ++k) even[k] = raw[2 * k], odd[k] = raw[2 * k + 1];
  if (n & 1) even[half - 1] = raw[n - 1];
  uint8_t before = out[0];
  for (size_t i = 1; i < n; ++i) {
    const uint8_t v = out[i];
    out[i] = uint8_t(v - before + 128);
    before = v;
  }
}

// A ZIP chunk's data: the prepared bytes as a zlib stream (RFC 1950: the
// fastest level's header, raw deflate, Adler-32 big-endian), or the raw
// bytes where that is no smaller, as OpenEXR stores them.
void putZipData(const unsigned char* raw, size_t n, int width, std::vector<unsigned char>& out) {
  thread_local std::vector<uint8_t> prepared;
  thread_local std::vector<unsigned char> stream;
  interleaveAndPredict(raw, n, prepared);
  stream.assign({0x78, 0x01});
  RowDeflater coder;
  // Equal differences repeat a byte before (runs, flat depth) or a row
  // before: a row is 2 width bytes in each half.
  coder.block(std::span(prepared), 0, 1, 2 * size_t(width), true, stream);
  const uint32_t adler = adler32Update(1, prepared);
  for (int shift = 24; shift >= 0; shift -= 8) stream.push_back(uint8_t(adler >> shift));
  if (stream.size() < n) out.insert(out.end(), stream.begin(), stream.end());
  else out.insert(out.end(), raw, raw + n);
}

}  // namespace

void encodeDepthExr(const DepthImage& depth, bool zip, std::vector<unsigned char>& out) {
  const int w = depth.width, h = depth.height;
  if (w <= 0 || h <= 0 || depth.values.size() != size_t(w) * h) throw Error("a depth image has no pixels");
  out.clear();
  putHeader(out, w, h, zip);
  const int lines = zip ? kZipLines : 1, chunks = (h + lines - 1) / lines;
  const size_t table = out.size();
  out.resize(table + 8 * size_t(chunks));  // the chunks' offsets, filled in as they are written
  for (int c = 0; c < chunks; ++c) {
    const uint64_t at = out.size();
    std::memcpy(out.data() + table + 8 * size_t(c), &at, 8);
    const int y = c * lines, count = std::min(lines, h - y);
    put(out, int32_t(y));
    const size_t sizeAt = out.size();
    put(out, int32_t(0));
    const auto* raw = reinterpret_cast<const unsigned char*>(depth.values.data() + size_t(y) * w);
    const size_t n = size_t(count) * w * sizeof(float);
    if (zip) putZipData(raw, n, w, out);
    else out.insert(out.end(), raw, raw + n);
    const int32_t size = int32_t(out.size() - sizeAt - 4);
    std::memcpy(out.data() + sizeAt, &size, 4);
  }
}

}  // namespace mvr
