#pragma once
// PNG files written by our own encoder over zlib, not through the
// OpenImageIO module: a whole render writes PNGs by default, and loading
// OpenImageIO's 260 libraries to write them cost 0.5 s of every render's
// start-up (docs/BENCHMARKS.md). PNG is a few chunks around one deflate
// stream of filtered rows (RFC 2083); the rows are fed one at a time, so
// an image can be encoded as its rows arrive.
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace mvr {

// What one file stores: RGBA of 8 or 16 bits per sample, zlib level 0..9,
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
  bool finished() const { return rowsLeft_ == 0; }

  // Rows are deflated in segments of about this many bytes, each by a
  // deflate stream reset for it and ended by a sync flush, stored as one
  // IDAT chunk: an encoder holds one segment, not a deflate stream's 256
  // KiB, so a thousand views can be encoded side by side as their rows
  // arrive, and a file's bytes depend on its pixels alone, however they
  // were fed. A segment starts from the last kDictionaryRows rows of the
  // one before as its history: a row's best match is mostly the row
  // above. Measured on a rendered 640x480 teacup view at level 1: 64 KiB
  // segments with 2 rows of history 66.1 KB in 2.7 ms, OpenImageIO's
  // libpng 66.8 KB in 2.9-3.5 ms; with no history 69.8 KB, with 32 KiB of
  // it 65.4 KB in 3.4 ms (the history is hashed again per segment).
  static constexpr size_t kSegmentBytes = size_t(64) << 10;
  static constexpr size_t kDictionaryRows = 2;

 private:
  void stageRow(std::span<const uint8_t> row);
  void deflateSegment(bool last);

  PngFormat format_;
  std::vector<unsigned char>& out_;
  size_t rowBytes_ = 0;
  int rowsLeft_ = 0, segmentRows_ = 1;
  std::vector<uint8_t> staged_;           // filtered rows (filter byte + row) not yet deflated
  std::vector<uint8_t> dictionary_;       // the end of the last segment, the next one's history
  std::vector<uint8_t> previous_, trial_;  // the adaptive filters' rows
  unsigned long adler_ = 0;                // the stream's checksum so far
  bool started_ = false;                   // the zlib header is out
};

// Row filters: none at the fast levels, the adaptive choice (libpng's
// heuristic: least sum of absolute values) from 4 on. Measured at level 1
// on rendered 640x480 views (docs/BENCHMARKS.md): no filter encodes 2-3x
// faster for files 2% smaller to 14% larger.
inline bool pngFilters(int level) { return level > 3; }

}  // namespace mvr
