// The row coder (mvr/images/row_deflate.h) against zlib's inflate: whatever it
// is fed, the blocks it writes must inflate to the bytes it was given.
// Each case aims at one part of the format: runs at the longest match,
// literals with no match, Huffman codes that must be cut to 15 bits,
// empty and one-byte blocks, bits carried from block to block, matches
// into the history, and distances deflate cannot code.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
#include <vector>

#include "mvr/images/row_deflate.h"

namespace mvr {
namespace {

// A raw deflate stream (no zlib wrapper) inflated; empty on any error.
std::vector<uint8_t> inflateRaw(const std::vector<unsigned char>& stream, size_t expected) {
  std::vector<uint8_t> out(expected + 64);
  z_stream z{};
  if (inflateInit2(&z, -15) != Z_OK) return {};
  z.next_in = const_cast<unsigned char*>(stream.data());
  z.avail_in = uInt(stream.size());
  z.next_out = out.data();
  z.avail_out = uInt(out.size());
  const int result = inflate(&z, Z_FINISH);
  const size_t produced = z.total_out;
  const bool consumed = z.avail_in == 0;
  inflateEnd(&z);
  if (result != Z_STREAM_END || !consumed) return {};
  out.resize(produced);
  return out;
}

// `data` coded as blocks of `block` bytes, each with the bytes before it
// (up to the window) as history, as the PNG encoder feeds its segments.
std::vector<unsigned char> deflateInBlocks(const std::vector<uint8_t>& data, size_t block, size_t pixel, size_t row) {
  RowDeflater coder;
  std::vector<unsigned char> out;
  size_t begin = 0;
  do {
    const size_t end = std::min(data.size(), begin + block);
    const size_t history = std::min<size_t>(begin, 32768);
    coder.block(std::span(data.data() + begin - history, end - begin + history), history, pixel, row,
                end == data.size(), out);
    begin = end;
  } while (begin < data.size());
  return out;
}

void expectRoundTrip(const std::vector<uint8_t>& data, size_t block, size_t pixel, size_t row, const char* what) {
  const std::vector<unsigned char> stream = deflateInBlocks(data, block, pixel, row);
  EXPECT_EQ(inflateRaw(stream, data.size()), data) << what << ", blocks of " << block << ", distances " << pixel
                                                   << " and " << row;
}

std::vector<uint8_t> noise(size_t n, uint32_t seed) {
  std::vector<uint8_t> v(n);
  for (uint8_t& b : v) seed = seed * 1664525u + 1013904223u, b = uint8_t(seed >> 24);
  return v;
}

TEST(RowDeflate, RunsAndNoiseInflateToTheirBytes) {
  const std::vector<uint8_t> zeros(100000, 0), noisy = noise(70001, 3);
  // Rows of a flat colour with noise between: matches at both distances.
  std::vector<uint8_t> image;
  for (int y = 0; y < 60; ++y)
    for (int x = 0; x < 257; ++x) {
      const uint8_t pixel[4] = {uint8_t(x < 100 ? 40 : x * y), uint8_t(x < 100 ? 80 : y), 7, 255};
      image.insert(image.end(), pixel, pixel + 4);
    }
  for (size_t block : {size_t(7), size_t(1000), size_t(32768), size_t(1) << 20})
    for (auto [pixel, row] : {std::pair<size_t, size_t>{4, 1029}, {4, 0}, {8, 1029}, {1, 3}}) {
      expectRoundTrip(zeros, block, pixel, row, "zeros");
      expectRoundTrip(noisy, block, pixel, row, "noise");
      expectRoundTrip(image, block, pixel, row, "rows");
    }
  // One byte a block: every block's few bits carried into the next.
  expectRoundTrip(std::vector<uint8_t>(image.begin(), image.begin() + 3000), 1, 4, 1029, "rows a byte a block");
}

// Runs compress to almost nothing, noise to about its size: the coder
// finds the matches and does not blow literals up.
TEST(RowDeflate, RunsShrinkAndNoiseStaysItsSize) {
  const std::vector<uint8_t> zeros(100000, 0), noisy = noise(100000, 11);
  EXPECT_LT(deflateInBlocks(zeros, 32768, 4, 1001).size(), 500u);
  EXPECT_LT(deflateInBlocks(noisy, 32768, 4, 1001).size(), 100000u * 101 / 100);
}

// Literal counts in Fibonacci proportion make an optimal Huffman code
// deeper than deflate's 15 bits: the lengths must be cut, and the code
// must stay complete, or inflate refuses it.
TEST(RowDeflate, CodesDeeperThanFifteenBitsAreCut) {
  std::vector<uint8_t> data;
  uint32_t a = 1, b = 1;
  for (int symbol = 0; symbol < 24; ++symbol) {
    for (uint32_t k = 0; k < a; ++k) data.push_back(uint8_t(symbol * 10 + k % 3));  // no repeats four bytes back
    const uint32_t next = a + b;
    a = b;
    b = next;
  }
  expectRoundTrip(data, data.size(), 4, 0, "Fibonacci counts");
}

TEST(RowDeflate, EmptyAndOneByteBlocksAndCarriedBits) {
  for (size_t n : {size_t(1), size_t(2), size_t(3), size_t(5)}) expectRoundTrip(noise(n, 5), n, 4, 0, "tiny");
  // An empty last block after data: the stream still ends.
  RowDeflater coder;
  std::vector<unsigned char> out;
  const std::vector<uint8_t> data = noise(300, 9);
  coder.block(std::span(data), 0, 4, 0, false, out);
  coder.block(std::span(data), data.size(), 4, 0, true, out);
  EXPECT_EQ(inflateRaw(out, data.size()), data);
}

// A block whose rows repeat its history's last row codes them as matches
// a row back: much smaller than with no history.
TEST(RowDeflate, MatchesReachIntoTheHistory) {
  const size_t row = 2001;
  std::vector<uint8_t> rows = noise(row, 21);
  for (int k = 0; k < 4; ++k) rows.insert(rows.end(), rows.begin(), rows.begin() + row);
  RowDeflater with, without;
  std::vector<unsigned char> a, b;
  with.block(std::span(rows), row, 4, row, true, a);
  without.block(std::span(rows.data() + row, rows.size() - row), 0, 4, row, true, b);
  EXPECT_LT(a.size() * 10, b.size());
  // The first row, the stream before the block, then the block's output.
  std::vector<unsigned char> stream;
  RowDeflater first;
  first.block(std::span(rows.data(), row), 0, 4, row, false, stream);
  first.block(std::span(rows), row, 4, row, true, stream);
  EXPECT_EQ(inflateRaw(stream, rows.size()), rows);
}

// Rows longer than deflate's window cannot be reached a row back: the
// coder must not code that distance, and still code the pixel before.
TEST(RowDeflate, RowsBeyondTheWindowAreNotMatched) {
  const size_t row = 40000;
  std::vector<uint8_t> rows = noise(row, 2);
  rows.insert(rows.end(), rows.begin(), rows.end());
  expectRoundTrip(rows, rows.size(), 4, row, "40000-byte rows");
}

}  // namespace
}  // namespace mvr
