#pragma once
// A deflate coder (RFC 1951) for image rows, PNG's fastest level. A
// rendered view repeats itself at two distances: the pixel before (flat
// colour, empty background) and the pixel above (the row before, through
// a row's filter byte). zlib's fast level hashes every position to find
// matches at any distance; this coder looks at those two alone, greedily,
// eight bytes a compare, and codes literals and matches with Huffman codes
// built for each block. Measured on rendered views (docs/BENCHMARKS.md):
// several times zlib level 1's speed for files of about its size.
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace mvr {

class RowDeflater {
 public:
  // Codes data[begin, end) as one block with its own Huffman codes,
  // appending whole bytes to out; data[0, begin) is earlier bytes of the
  // stream that matches may reach (at most 32 KiB back). The bits of a
  // byte not yet full are carried to the next block. `pixel` is the
  // distance to the pixel before, `row` to the pixel above (0: none).
  // The last block is marked final and ends on a byte.
  void block(std::span<const uint8_t> data, size_t begin, size_t pixel, size_t row, bool last,
             std::vector<unsigned char>& out);

 private:
  uint64_t bits_ = 0;  // bits not yet written, the first in the lowest place
  int count_ = 0;
};

}  // namespace mvr
