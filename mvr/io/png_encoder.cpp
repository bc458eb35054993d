#include "mvr/io/png_encoder.h"

#include <zlib.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>

#include "mvr/error.h"

namespace mvr {
namespace {

constexpr unsigned char kSignature[8] = {137, 'P', 'N', 'G', '\r', '\n', 26, '\n'};
// IDAT chunks of at most this many bytes (a chunk may hold 2^31 - 1).
constexpr size_t kIdatChunk = size_t(1) << 20;

void put32(std::vector<unsigned char>& out, uint32_t v) {
  const unsigned char b[4] = {uint8_t(v >> 24), uint8_t(v >> 16), uint8_t(v >> 8), uint8_t(v)};
  out.insert(out.end(), b, b + 4);
}

void putChunk(std::vector<unsigned char>& out, const char type[4], std::span<const unsigned char> data) {
  put32(out, uint32_t(data.size()));
  const size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put32(out, uint32_t(crc32(0, out.data() + start, uInt(out.size() - start))));
}

std::vector<unsigned char> be32(std::initializer_list<uint32_t> values) {
  std::vector<unsigned char> out;
  for (uint32_t v : values) put32(out, v);
  return out;
}

void checkText(const std::string& key, const std::string& value) {
  const bool keyOk = !key.empty() && key.size() <= 79 && key.find('\0') == std::string::npos &&
                     key.front() != ' ' && key.back() != ' ';
  if (!keyOk) throw Error("a text chunk's key must be 1 to 79 characters with no leading or trailing space: '" +
                              key + "'");
  if (value.find('\0') != std::string::npos) throw Error("text '" + key + "' holds a NUL character");
}

// The header chunks: IHDR, then the colour encoding, then the text.
void putHeader(std::vector<unsigned char>& out, const PngFormat& f) {
  out.assign(kSignature, kSignature + 8);
  std::vector<unsigned char> ihdr = be32({uint32_t(f.width), uint32_t(f.height)});
  ihdr.insert(ihdr.end(), {uint8_t(f.bits), 6 /* RGBA */, 0, 0, 0 /* deflate, adaptive filters, no interlace */});
  putChunk(out, "IHDR", ihdr);
  if (f.srgb) {
    // sRGB with the gAMA and cHRM values the PNG specification gives for
    // decoders that do not know the sRGB chunk.
    putChunk(out, "gAMA", be32({45455}));
    const unsigned char intent = 0;  // perceptual
    putChunk(out, "sRGB", std::span(&intent, 1));
    putChunk(out, "cHRM", be32({31270, 32900, 64000, 33000, 30000, 60000, 15000, 6000}));
  } else {
    putChunk(out, "gAMA", be32({100000}));  // gamma 1.0: linear
  }
  for (const auto& [key, value] : f.text) {
    checkText(key, value);
    std::vector<unsigned char> data(key.begin(), key.end());
    data.push_back(0);
    data.insert(data.end(), value.begin(), value.end());
    putChunk(out, "tEXt", data);
  }
}

uint8_t paeth(int a, int b, int c) {
  const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
  return uint8_t(pa <= pb && pa <= pc ? a : pb <= pc ? b : c);
}

// Row `cur` filtered by `type` into out[1..] (out[0] = type); prev is the
// row above (zeros for the first); bpp bytes per pixel.
void applyFilter(int type, const uint8_t* cur, const uint8_t* prev, size_t n, size_t bpp, uint8_t* out) {
  out[0] = uint8_t(type);
  ++out;
  for (size_t i = 0; i < n; ++i) {
    const int a = i >= bpp ? cur[i - bpp] : 0, b = prev[i], c = i >= bpp ? prev[i - bpp] : 0;
    const int predicted = type == 1 ? a : type == 2 ? b : type == 3 ? (a + b) / 2 : type == 4 ? paeth(a, b, c) : 0;
    out[i] = uint8_t(cur[i] - predicted);
  }
}

// libpng's heuristic for the adaptive choice: the filtered bytes read as
// signed, least sum of absolute values.
size_t filterCost(const uint8_t* filtered, size_t n) {
  size_t sum = 0;
  for (size_t i = 0; i < n; ++i) sum += size_t(std::abs(int(int8_t(filtered[i]))));
  return sum;
}

}  // namespace

// A deflate stream, kept for the next image: deflateInit allocates 256
// KiB, and fresh pages per file cost page faults that serialise the
// encoders on the kernel's memory lock.
struct PngStream {
  z_stream z{};
  int level = -1, strategy = -1;
  std::vector<unsigned char> idat;  // the compressed rows: idat[0, used)
  size_t used = 0;
};

namespace {

std::mutex& spareMutex() {
  static std::mutex m;
  return m;
}

std::vector<std::unique_ptr<PngStream>>& spares() {
  static std::vector<std::unique_ptr<PngStream>> s;
  return s;
}

}  // namespace

PngEncoder::PngEncoder(const PngFormat& format, std::vector<unsigned char>& out) : format_(format), out_(out) {
  if (format.width <= 0 || format.height <= 0) throw Error("an image has no pixels");
  if (format.bits != 8 && format.bits != 16) throw Error("stores 8 or 16 bits per sample here");
  if (format.level < 0 || format.level > 9) throw Error("zlib level must be 0..9");
  rowBytes_ = size_t(format.width) * 4 * (format.bits / 8);
  rowsLeft_ = format.height;
  putHeader(out_, format_);
  previous_.assign(rowBytes_, 0);
  filtered_.resize(rowBytes_ + 1);
  if (pngFilters(format.level)) trial_.resize(rowBytes_ + 1);
  // libpng's choice: Z_FILTERED where rows are filtered.
  const int strategy = pngFilters(format.level) ? Z_FILTERED : Z_DEFAULT_STRATEGY;
  {
    std::lock_guard lock(spareMutex());
    auto& s = spares();
    for (auto it = s.begin(); it != s.end(); ++it)
      if ((*it)->level == format.level && (*it)->strategy == strategy) {
        stream_ = it->release();
        s.erase(it);
        break;
      }
  }
  if (stream_) {
    deflateReset(&stream_->z);
  } else {
    auto stream = std::make_unique<PngStream>();
    if (deflateInit2(&stream->z, format.level, Z_DEFLATED, 15, 8, strategy) != Z_OK)
      throw Error("cannot start a deflate stream");
    stream->level = format.level;
    stream->strategy = strategy;
    stream_ = stream.release();
  }
  stream_->used = 0;
}

PngEncoder::~PngEncoder() {
  if (stream_->idat.size() > (size_t(16) << 20)) stream_->idat = {};  // a huge image's room is not kept
  std::lock_guard lock(spareMutex());
  if (spares().size() < 64) {
    spares().emplace_back(stream_);
  } else {
    deflateEnd(&stream_->z);
    delete stream_;
  }
}

void PngEncoder::filterRow(std::span<const uint8_t> row) {
  const size_t bpp = 4 * size_t(format_.bits / 8);
  if (!pngFilters(format_.level)) {
    filtered_[0] = 0;
    std::memcpy(filtered_.data() + 1, row.data(), rowBytes_);
    return;
  }
  size_t best = SIZE_MAX;
  for (int type = 0; type <= 4; ++type) {
    applyFilter(type, row.data(), previous_.data(), rowBytes_, bpp, trial_.data());
    if (const size_t cost = filterCost(trial_.data() + 1, rowBytes_); cost < best) {
      best = cost;
      filtered_.swap(trial_);
    }
  }
  std::memcpy(previous_.data(), row.data(), rowBytes_);
}

void PngEncoder::deflateRow(bool last) {
  z_stream& z = stream_->z;
  std::vector<unsigned char>& idat = stream_->idat;
  z.next_in = filtered_.data();
  z.avail_in = uInt(filtered_.size());
  for (;;) {
    if (stream_->used == idat.size()) idat.resize(std::max<size_t>(size_t(64) << 10, idat.size() * 2));
    z.next_out = idat.data() + stream_->used;
    z.avail_out = uInt(std::min<size_t>(idat.size() - stream_->used, UINT32_MAX));
    const int result = deflate(&z, last ? Z_FINISH : Z_NO_FLUSH);
    stream_->used = idat.size() - z.avail_out;
    if (result == Z_STREAM_END) return;
    if (result != Z_OK && result != Z_BUF_ERROR) throw Error("deflate failed");
    if (!last && z.avail_in == 0) return;
  }
}

void PngEncoder::addRow(std::span<const uint8_t> samples) {
  if (rowsLeft_ == 0) throw Error("more rows than the image has");
  if (samples.size() != rowBytes_) throw Error("a row of the wrong length");
  filterRow(samples);
  --rowsLeft_;
  deflateRow(rowsLeft_ == 0);
  if (rowsLeft_ > 0) return;
  const std::span<const unsigned char> idat(stream_->idat.data(), stream_->used);
  for (size_t at = 0; at < idat.size(); at += kIdatChunk)
    putChunk(out_, "IDAT", idat.subspan(at, std::min(kIdatChunk, idat.size() - at)));
  putChunk(out_, "IEND", {});
}

}  // namespace mvr
