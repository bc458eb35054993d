#include "mvr/images/png_encoder.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cstdlib>
#include <cstring>
#include <memory>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

#include "mvr/color.h"
#include "mvr/error.h"
#include "mvr/images/adler32.h"
#include "mvr/images/row_deflate.h"

namespace mvr {
namespace {

constexpr unsigned char kSignature[8] = {137, 'P', 'N', 'G', '\r', '\n', 26, '\n'};

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

// The Up filter of n bytes of row into out, and row kept in above for the
// next row: one pass, 16 bytes a step (GCC's -O2 does not vectorise a
// loop whose pointers it cannot prove apart).
void upFilter(const uint8_t* row, uint8_t* above, uint8_t* out, size_t n) {
  size_t i = 0;
#ifdef __SSE2__
  for (; i + 16 <= n; i += 16) {
    const __m128i r = _mm_loadu_si128(reinterpret_cast<const __m128i*>(row + i));
    const __m128i a = _mm_loadu_si128(reinterpret_cast<const __m128i*>(above + i));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + i), _mm_sub_epi8(r, a));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(above + i), r);
  }
#endif
  for (; i < n; ++i) out[i] = uint8_t(row[i] - above[i]), above[i] = row[i];
}

// libpng's heuristic for the adaptive choice: the filtered bytes read as
// signed, least sum of absolute values.
size_t filterCost(const uint8_t* filtered, size_t n) {
  size_t sum = 0;
  for (size_t i = 0; i < n; ++i) sum += size_t(std::abs(int(int8_t(filtered[i]))));
  return sum;
}

// A worker's raw deflate stream, reset for every segment: deflateInit
// allocates 256 KiB, and fresh pages per file cost page faults that
// serialise the encoders on the kernel's memory lock.
struct Deflater {
  z_stream z{};
  int level = -1, strategy = -1;
  std::vector<unsigned char> chunk;  // an IDAT chunk's data as it is made

  ~Deflater() {
    if (level >= 0) deflateEnd(&z);
  }
  z_stream& reset(int newLevel, int newStrategy) {
    if (newLevel == level && newStrategy == strategy) {
      deflateReset(&z);
      return z;
    }
    if (level >= 0) deflateEnd(&z);
    level = -1;
    z = {};
    // Raw deflate (no zlib wrapper): the encoder writes the one header and
    // the one checksum of the file's stream around its segments.
    if (deflateInit2(&z, newLevel, Z_DEFLATED, -15, 8, newStrategy) != Z_OK)
      throw Error("cannot start a deflate stream");
    level = newLevel;
    strategy = newStrategy;
    return z;
  }
};

Deflater& deflater() {
  thread_local Deflater d;
  return d;
}

// The zlib header (RFC 1950): deflate with a 32 KiB window, FLEVEL from
// the level, FCHECK making the pair a multiple of 31.
std::array<unsigned char, 2> zlibHeader(int level) {
  const int flevel = level < 2 ? 0 : level < 6 ? 1 : level == 6 ? 2 : 3;
  const unsigned cmf = 0x78, flg = unsigned(flevel) << 6;
  return {uint8_t(cmf), uint8_t(flg + (31 - (cmf * 256 + flg) % 31) % 31)};
}

size_t rowBytesOf(const PngFormat& format) { return size_t(format.width) * 4 * (format.bits / 8); }
int segmentRowsOf(const PngFormat& format) {
  return int(std::clamp<size_t>(PngEncoder::kSegmentBytes / (rowBytesOf(format) + 1), 1, size_t(format.height)));
}

}  // namespace

size_t PngEncoder::heldBytes(const PngFormat& format) {
  const size_t row = rowBytesOf(format) + 1;
  // previous_, and trial_ for the adaptive choice
  const size_t filters = pngFilters(format.level) ? 2 * row : ownDeflate(format.level) ? row : 0;
  return (kDictionaryRows + size_t(segmentRowsOf(format))) * row + filters + sizeof(PngEncoder);
}

PngEncoder::PngEncoder(const PngFormat& format, std::vector<unsigned char>& out) : format_(format), out_(out) {
  if (format.width <= 0 || format.height <= 0) throw Error("an image has no pixels");
  if (format.bits != 8 && format.bits != 16) throw Error("stores 8 or 16 bits per sample here");
  if (format.level < 0 || format.level > 9) throw Error("zlib level must be 0..9");
  rowBytes_ = rowBytesOf(format);
  rowsLeft_ = format.height;
  segmentRows_ = segmentRowsOf(format);
  putHeader(out_, format_);
  if (pngFilters(format.level) || ownDeflate(format.level)) previous_.assign(rowBytes_, 0);
  if (pngFilters(format.level)) trial_.resize(rowBytes_ + 1);
}

void PngEncoder::stageRow(std::span<const uint8_t> row) {
  // Not zero-filled: every byte is written before it is read.
  if (!staged_)
    staged_ = std::make_unique_for_overwrite<uint8_t[]>((kDictionaryRows + size_t(segmentRows_)) * (rowBytes_ + 1));
  uint8_t* out = staged_.get() + stagedEnd_;
  stagedEnd_ += rowBytes_ + 1;
  if (ownDeflate(format_.level)) {
    // The Up filter: a row repeated leaves zeros, a vertical gradient a
    // constant, which the coder's matches take in long runs.
    out[0] = 2;
    upFilter(row.data(), previous_.data(), out + 1, rowBytes_);
    return;
  }
  if (!pngFilters(format_.level)) {
    out[0] = 0;
    std::memcpy(out + 1, row.data(), rowBytes_);
    return;
  }
  const size_t bpp = 4 * size_t(format_.bits / 8);
  size_t best = SIZE_MAX;
  for (int type = 0; type <= 4; ++type) {
    applyFilter(type, row.data(), previous_.data(), rowBytes_, bpp, trial_.data());
    if (const size_t cost = filterCost(trial_.data() + 1, rowBytes_); cost < best) {
      best = cost;
      std::memcpy(out, trial_.data(), rowBytes_ + 1);
    }
  }
  std::memcpy(previous_.data(), row.data(), rowBytes_);
}

// zlib's deflate of rows after the history staged before them, appended
// to chunk, ending on a byte boundary (a sync flush) unless last.
void PngEncoder::zlibDeflate(std::span<const uint8_t> rows, bool last, std::vector<unsigned char>& chunk) const {
  z_stream& z = deflater().reset(format_.level, pngFilters(format_.level) ? Z_FILTERED : Z_DEFAULT_STRATEGY);
  size_t used = chunk.size();
  chunk.resize(used + deflateBound(&z, uLong(rows.size())) + 16);
  if (history_ > 0) deflateSetDictionary(&z, staged_.get(), uInt(history_));
  z.next_in = const_cast<uint8_t*>(rows.data());  // zlib's API is not const
  z.avail_in = uInt(rows.size());
  for (;;) {
    z.next_out = chunk.data() + used;
    z.avail_out = uInt(chunk.size() - used);
    const int result = deflate(&z, last ? Z_FINISH : Z_SYNC_FLUSH);
    used = chunk.size() - z.avail_out;
    if (result != Z_OK && result != Z_STREAM_END && result != Z_BUF_ERROR) throw Error("deflate failed");
    if (last ? result == Z_STREAM_END : z.avail_in == 0 && z.avail_out > 0) break;
    chunk.resize(chunk.size() * 2);
  }
  chunk.resize(used);
}

// The staged rows as one IDAT chunk: deflated on their own, by zlib
// ending on a byte boundary (a sync flush), by our coder (level 1) as one
// block whose last bits short of a byte open the next chunk.
void PngEncoder::deflateSegment(bool last) {
  std::vector<unsigned char>& chunk = deflater().chunk;
  const bool first = !started_;
  started_ = true;
  chunk.clear();
  if (first) {
    const auto header = zlibHeader(format_.level);
    chunk.assign(header.begin(), header.end());
  }
  const std::span<const uint8_t> rows(staged_.get() + history_, stagedEnd_ - history_);
  if (ownDeflate(format_.level))
    rowDeflater_.block(std::span(staged_.get(), stagedEnd_), history_, 4 * size_t(format_.bits / 8), rowBytes_ + 1,
                       last, chunk);
  else
    zlibDeflate(rows, last, chunk);
  size_t used = chunk.size();
  adler_ = adler32Update(first ? 1u : uint32_t(adler_), rows);
  // The segment's last rows are the next one's history.
  history_ = std::min(stagedEnd_, kDictionaryRows * (rowBytes_ + 1));
  std::memmove(staged_.get(), staged_.get() + stagedEnd_ - history_, history_);
  stagedEnd_ = history_;
  if (last) {
    staged_.reset();
    chunk.resize(used);
    put32(chunk, uint32_t(adler_));
    used = chunk.size();
  }
  putChunk(out_, "IDAT", std::span(chunk.data(), used));
}

namespace {

template <typename T>
T quantise(float v) {
  constexpr float top = float(T(~T(0)));
  return v >= 0.0f ? (v < 1.0f ? T(v * top + 0.5f) : T(~T(0))) : T(0);
}

}  // namespace

std::span<const uint8_t> pngRow(const Image& pixels, int y, int bits, bool encode, std::vector<uint8_t>& room) {
  if (isByteType(pixels.type)) return {pixels.row(y), pixels.rowBytes()};
  const float* v = reinterpret_cast<const float*>(pixels.row(y));
  const size_t n = size_t(pixels.width) * 4;
  room.resize(n * size_t(bits / 8));
  for (size_t i = 0; i < n; ++i) {
    const float f = encode && i % 4 != 3 ? srgbEncode(v[i]) : v[i];
    if (bits == 8) {
      room[i] = quantise<uint8_t>(f);
    } else {
      const uint16_t q = quantise<uint16_t>(f);
      room[2 * i] = uint8_t(q >> 8);
      room[2 * i + 1] = uint8_t(q);
    }
  }
  return room;
}

void PngEncoder::addRow(std::span<const uint8_t> samples) {
  if (rowsLeft_ == 0) throw Error("more rows than the image has");
  if (samples.size() != rowBytes_) throw Error("a row of the wrong length");
  stageRow(samples);
  --rowsLeft_;
  if (rowsLeft_ == 0 || stagedEnd_ - history_ == size_t(segmentRows_) * (rowBytes_ + 1)) deflateSegment(rowsLeft_ == 0);
  if (rowsLeft_ == 0) putChunk(out_, "IEND", {});
}

}  // namespace mvr
