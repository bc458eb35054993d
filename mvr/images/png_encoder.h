#pragma once
// PNG files written by our own encoder (zlib's deflate, or at level 1
// our row coder, mvr/images/row_deflate.h), not through the
// OpenImageIO module: a whole render writes PNGs by default, and loading
// OpenImageIO's 260 libraries to write them cost 0.5 s of every render's
// start-up (docs/BENCHMARKS.md). PNG is a few chunks around one deflate
// stream of filtered rows (RFC 2083); the rows are fed one at a time, so
// an image can be encoded as its rows arrive.
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "mvr/image.h"
#include "mvr/images/row_deflate.h"

namespace mvr {

// What one file stores: RGBA of 8 or 16 bits per sample, level 0..9
// (1: our row coder; else zlib's level),
// tagged sRGB (sRGB, gAMA and cHRM chunks) or linear (gAMA 1.0), and
// string metadata as tEXt chunks (keys of 1 to 79 Latin-1 characters).
struct PngFormat {
  int width = 0, height = 0;
  int bits = 8;
  int level = 1;
  bool srgb = true;
  std::vector<std::pair<std::string, std::string>> text = {};
};

class PngEncoder {
 public:
  // Writes the signature and the chunks before the pixels into out
  // (cleared); the rest follows as rows come, the last row finishing the
  // file. Throws mvr::Error with the reason (the caller names the file)
  // for a format PNG cannot store. out must outlive the encoder.
  PngEncoder(const PngFormat& format, std::vector<unsigned char>& out);

  // The next row, top first: width * 4 samples as the file stores them
  // (bytes, or 16-bit values big-endian).
  void addRow(std::span<const uint8_t> samples);
  // Bytes of one row as addRow takes it.
  size_t rowBytes() const { return rowBytes_; }
  // The memory an encoder of this format holds besides its output.
  static size_t heldBytes(const PngFormat& format);
  bool finished() const { return rowsLeft_ == 0; }

  // Rows are deflated in segments of about this many bytes, each by a
  // deflate stream reset for it and ended by a sync flush (at level 1: one
  // block of our coder's), stored as one IDAT chunk: an encoder holds one segment, not a deflate stream's 256
  // KiB, so a thousand views can be encoded side by side as their rows
  // arrive (mvr/frames/png_views.h), and a file's bytes depend on its pixels
  // alone, however they were fed. A segment starts from the last
  // kDictionaryRows rows of the one before as its history: a row's best
  // match is mostly the row above. Measured with zlib's level 1 on the rendered
  // 143K teacup (docs/BENCHMARKS.md): a 640x480 view in 2.0 ms and 66.7
  // KB (libpng through OpenImageIO: 2.9 ms, 66.8 KB; no history: 74.6 KB;
  // 32 KiB of it: 3.7 ms, the history hashed again per segment); 1000
  // views of 160x140 fed row by row side by side, 0.29 ms a view (16 KiB
  // segments 0.25 ms, 64 KiB 0.38 ms: a segment's first touch).
  static constexpr size_t kSegmentBytes = size_t(32) << 10;
  static constexpr size_t kDictionaryRows = 2;

 private:
  void stageRow(std::span<const uint8_t> row);
  void deflateSegment(bool last);
  void zlibDeflate(std::span<const uint8_t> rows, bool last, std::vector<unsigned char>& chunk) const;

  PngFormat format_;
  std::vector<unsigned char>& out_;
  size_t rowBytes_ = 0;
  int rowsLeft_ = 0, segmentRows_ = 1;
  // Filtered rows (filter byte + row): [0, history_) the last rows of the
  // segment before, [history_, stagedEnd_) those not yet deflated.
  std::unique_ptr<uint8_t[]> staged_;
  size_t history_ = 0, stagedEnd_ = 0;
  std::vector<uint8_t> previous_, trial_;  // the adaptive filters' rows
  unsigned long adler_ = 0;                // the stream's checksum so far
  bool started_ = false;                   // the zlib header is out
  RowDeflater rowDeflater_;                // level 1's coder, its bits carried from segment to segment
};

// Row y of an image as a PNG of `bits` (8 or 16) stores it: a byte
// image's row as it is; a float one's sRGB-encoded first where `encode`
// (alpha never), rounded, clamped (NaN to 0), 16-bit values big-endian,
// into `room`. The samples writeImage and the EPI-fed view encoders
// (mvr/frames/png_views.h) both give addRow.
std::span<const uint8_t> pngRow(const Image& pixels, int y, int bits, bool encode, std::vector<uint8_t>& room);

// Level 1, the default: every row by the Up filter, deflated by our row
// coder (mvr/images/row_deflate.h) instead of zlib.
inline bool ownDeflate(int level) { return level == 1; }
// zlib's levels: no filter at 2 and 3, the adaptive choice (libpng's
// heuristic: least sum of absolute values) from 4 on. Measured with zlib
// level 1 on rendered 640x480 views (docs/BENCHMARKS.md): no filter
// encodes 2-3x faster for files 2% smaller to 14% larger.
inline bool pngFilters(int level) { return level > 3; }

}  // namespace mvr
