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

struct PngStream;  // a deflate stream and its output, reused across images

class PngEncoder {
 public:
  // Writes the signature and the chunks before the pixels into out
  // (cleared). Throws mvr::Error with the reason (the caller names the
  // file) for a format PNG cannot store.
  PngEncoder(const PngFormat& format, std::vector<unsigned char>& out);
  ~PngEncoder();
  PngEncoder(const PngEncoder&) = delete;
  PngEncoder& operator=(const PngEncoder&) = delete;

  // The next row, top first: width * 4 samples as the file stores them
  // (bytes, or 16-bit values big-endian). The last row finishes the file.
  void addRow(std::span<const uint8_t> samples);
  // Bytes of one row as addRow takes it.
  size_t rowBytes() const { return rowBytes_; }
  bool finished() const { return rowsLeft_ == 0; }

 private:
  void filterRow(std::span<const uint8_t> samples);
  void deflateRow(bool last);

  PngFormat format_;
  std::vector<unsigned char>& out_;
  size_t rowBytes_ = 0;
  int rowsLeft_ = 0;
  std::vector<uint8_t> previous_, filtered_, trial_;  // filter byte + row
  PngStream* stream_ = nullptr;
};

// Row filters: none at the fast levels, the adaptive choice (libpng's
// heuristic: least sum of absolute values) from 4 on. Measured at level 1
// on rendered 640x480 views (docs/BENCHMARKS.md): no filter encodes 2-3x
// faster for files 2% smaller to 14% larger.
inline bool pngFilters(int level) { return level > 3; }

}  // namespace mvr
