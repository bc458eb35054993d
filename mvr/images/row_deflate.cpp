#include "mvr/images/row_deflate.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <numeric>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

namespace mvr {
namespace {

// RFC 1951, 3.2.5: lengths 3..258 as codes 257..285 with extra bits, and
// distances as codes 0..29.
constexpr std::array<uint16_t, 29> kLengthBase = {3,  4,  5,  6,  7,  8,  9,  10, 11,  13,  15,  17,  19,  23, 27,
                                                  31, 35, 43, 51, 59, 67, 83, 99, 115, 131, 163, 195, 227, 258};
constexpr std::array<uint8_t, 29> kLengthExtra = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                                  2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
constexpr std::array<uint16_t, 30> kDistanceBase = {1,    2,    3,    4,    5,    7,     9,     13,    17,  25,
                                                    33,   49,   65,   97,   129,  193,   257,   385,   513, 769,
                                                    1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
constexpr std::array<uint8_t, 30> kDistanceExtra = {0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
                                                    6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
// The order the code-length code's lengths are stored in (3.2.7).
constexpr std::array<uint8_t, 19> kCodeLengthOrder = {16, 17, 18, 0, 8, 7, 9, 6, 10, 5, 11, 4, 12, 3, 13, 2, 14, 1, 15};
constexpr size_t kMaxMatch = 258, kMinMatch = 3, kWindow = 32768;
constexpr int kLiterals = 286, kDistances = 30, kCodeLengths = 19, kEndOfBlock = 256;

// The code (index into kLengthBase) of each match length.
constexpr std::array<uint8_t, kMaxMatch + 1> lengthCodes() {
  std::array<uint8_t, kMaxMatch + 1> codes{};
  for (size_t len = kMinMatch, code = 0; len <= kMaxMatch; ++len) {
    while (code + 1 < kLengthBase.size() && kLengthBase[code + 1] <= len) ++code;
    codes[len] = uint8_t(code);
  }
  return codes;
}
constexpr std::array<uint8_t, kMaxMatch + 1> kLengthCode = lengthCodes();

int distanceCode(size_t distance) {
  int code = 0;
  while (code + 1 < kDistances && kDistanceBase[code + 1] <= distance) ++code;
  return code;
}

// How many bytes from a equal those from b, up to max; a and b may
// overlap (a run), as deflate's copies do.
[[gnu::always_inline]] inline size_t matchLength(const uint8_t* a, const uint8_t* b, size_t max) {
  size_t n = 0;
#ifdef __SSE2__
  for (; n + 16 <= max; n += 16) {
    const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(a + n));
    const __m128i y = _mm_loadu_si128(reinterpret_cast<const __m128i*>(b + n));
    if (const unsigned differ = ~unsigned(_mm_movemask_epi8(_mm_cmpeq_epi8(x, y))) & 0xffffu)
      return n + size_t(__builtin_ctz(differ));
  }
#endif
  for (; n + 8 <= max; n += 8) {
    uint64_t x, y;
    std::memcpy(&x, a + n, 8);
    std::memcpy(&y, b + n, 8);
    if (x != y) return n + size_t(__builtin_ctzll(x ^ y) >> 3);
  }
  while (n < max && a[n] == b[n]) ++n;
  return n;
}

// Huffman code lengths for `freq`, none longer than maxBits: the optimal
// tree's length counts, limited as JPEG's Annex K.3 does (a pair of the
// longest codes becomes one code a bit shorter and a shorter code splits),
// then given out shortest first to the most frequent symbols. At least
// two symbols get a length so that the code is complete, as inflaters
// require.
void codeLengths(std::span<uint32_t> freq, int maxBits, uint8_t* lengths) {
  const int n = int(freq.size());
  std::fill(lengths, lengths + n, 0);
  std::array<int, kLiterals> order;
  int used = 0;
  for (int s = 0; s < n; ++s)
    if (freq[s]) order[used++] = s;
  for (int s = 0; used < 2; ++s)
    if (!freq[s]) freq[s] = 1, order[used++] = s;
  std::sort(order.begin(), order.begin() + used,
            [&](int a, int b) { return freq[a] < freq[b] || (freq[a] == freq[b] && a < b); });
  // Two queues: leaves by weight, and merged nodes, made in weight order.
  std::array<uint64_t, kLiterals> weight;
  std::array<int, 2 * kLiterals> parent;
  int leaf = 0, merged = 0, made = 0;
  auto takeLightest = [&]() {
    if (leaf < used && (merged == made || freq[order[leaf]] <= weight[merged])) return leaf++;
    return used + merged++;
  };
  auto weightOf = [&](int node) { return node < used ? uint64_t(freq[order[node]]) : weight[node - used]; };
  while (made < used - 1) {
    const int a = takeLightest(), b = takeLightest();
    weight[made] = weightOf(a) + weightOf(b);
    parent[a] = parent[b] = used + made;
    ++made;
  }
  // Depths from the root (the last node made) down.
  std::array<int, 2 * kLiterals> depth;
  depth[used + made - 1] = 0;
  for (int node = used + made - 2; node >= 0; --node) depth[node] = depth[parent[node]] + 1;
  std::array<int, 64> count{};
  int longest = 0;
  for (int i = 0; i < used; ++i) ++count[depth[i]], longest = std::max(longest, depth[i]);
  for (int bits = longest; bits > maxBits; --bits) {
    while (count[bits] > 0) {
      int shorter = bits - 2;
      while (count[shorter] == 0) --shorter;
      count[bits] -= 2;
      count[bits - 1] += 1;
      count[shorter + 1] += 2;
      count[shorter] -= 1;
    }
  }
  for (int bits = 1, next = used - 1; bits <= maxBits; ++bits)
    for (int k = 0; k < count[bits]; ++k) lengths[order[next--]] = uint8_t(bits);
}

// Canonical codes from lengths (3.2.2), bit-reversed: deflate sends a
// code's first bit first, and the writer fills the lowest bits first.
void canonicalCodes(const uint8_t* lengths, int n, uint16_t* codes) {
  std::array<int, 16> count{}, next{};
  for (int s = 0; s < n; ++s) ++count[lengths[s]];
  count[0] = 0;
  for (int bits = 1, code = 0; bits < 16; ++bits) next[bits] = code = (code + count[bits - 1]) << 1;
  for (int s = 0; s < n; ++s) {
    const int len = lengths[s];
    if (!len) continue;
    uint32_t code = uint32_t(next[len]++), reversed = 0;
    for (int b = 0; b < len; ++b) reversed |= ((code >> b) & 1u) << (len - 1 - b);
    codes[s] = uint16_t(reversed);
  }
}

struct Code {
  std::array<uint8_t, kLiterals> length{};
  std::array<uint16_t, kLiterals> bits{};
  void build(std::span<uint32_t> freq, int maxBits) {
    codeLengths(freq, maxBits, length.data());
    canonicalCodes(length.data(), int(freq.size()), bits.data());
  }
};

// The code-length code's symbols for a run of lengths (3.2.7): 16 repeats
// the previous length 3-6 times, 17 and 18 give 3-10 and 11-138 zeros.
struct LengthSymbol {
  uint8_t symbol, extra;
};
std::vector<LengthSymbol>& lengthSymbols(const uint8_t* lengths, int n) {
  thread_local std::vector<LengthSymbol> out;
  out.clear();
  for (int i = 0; i < n;) {
    const uint8_t v = lengths[i];
    int run = 1;
    while (i + run < n && lengths[i + run] == v) ++run;
    i += run;
    if (v == 0) {
      for (; run >= 11; run -= std::min(run, 138)) out.push_back({18, uint8_t(std::min(run, 138) - 11)});
      if (run >= 3) out.push_back({17, uint8_t(run - 3)}), run = 0;
    } else {
      out.push_back({v, 0});
      --run;
      for (; run >= 3; run -= std::min(run, 6)) out.push_back({16, uint8_t(std::min(run, 6) - 3)});
    }
    for (; run > 0; --run) out.push_back({v, 0});
  }
  return out;
}

// Bits into bytes, the first bit in the lowest place (3.1.1).
struct BitSink {
  uint64_t bits;
  int count;
  unsigned char* at;
  // Up to 57 bits held: every put writes the eight lowest bytes and moves
  // on by the whole ones, which costs no branch (the buffer has room).
  void put(uint32_t value, int n) {
    bits |= uint64_t(value) << count;
    count += n;
    std::memcpy(at, &bits, 8);  // little-endian: the lowest byte first
    at += count >> 3;
    bits >>= count & ~7;
    count &= 7;
  }
};

// A block's tokens: a literal byte, or a match of `length` at the first
// or second distance, with the counts its Huffman codes are built from.
constexpr uint32_t kMatch = 1u << 31;
struct Tokens {
  std::span<const uint32_t> tokens;
  std::array<uint32_t, kLiterals> litFreq{};
  std::array<uint32_t, 2> uses{};  // matches at each distance
};

#ifdef __SSE2__
// The positions 0..13 of x where three bytes equal those at back.
unsigned threeByteStarts(__m128i x, const uint8_t* back) {
  const __m128i y = _mm_loadu_si128(reinterpret_cast<const __m128i*>(back));
  const unsigned eq = unsigned(_mm_movemask_epi8(_mm_cmpeq_epi8(x, y)));
  return eq & eq >> 1 & eq >> 2 & 0x3fffu;
}
#endif

// Greedy: at each byte the longer match of the two distances, if it is at
// least three bytes, else a literal.
void tokenize(std::span<const uint8_t> data, size_t begin, const size_t distance[2], Tokens& t) {
  thread_local std::vector<uint32_t> store;
  store.resize(std::max(store.size(), data.size() - begin));
  uint32_t* const first = store.data();
  uint32_t* token = first;
  // The literals of runs counted in four tables: a run of one value would
  // otherwise wait on its own count's increment each byte.
  std::array<std::array<uint32_t, 256>, 4> runFreq{};
  const uint8_t* p = data.data();
  const size_t pixel = distance[0], row = distance[1], reach = std::max(pixel, row);
  for (size_t i = begin, end = data.size(); i < end;) {
#ifdef __SSE2__
    // Literals 14 at a time: the first position where either distance
    // repeats three bytes, found from 16 bytes' equalities at once, so
    // that a run of literals costs no mispredicted branch a byte.
    if (pixel && i >= reach && end - i >= 16) {
      const __m128i x = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + i));
      const unsigned found = threeByteStarts(x, p + i - pixel) | (row ? threeByteStarts(x, p + i - row) : 0u);
      const size_t literals = found ? size_t(__builtin_ctz(found)) : 14;
      for (size_t k = 0; k < literals; ++k) *token++ = p[i + k], ++runFreq[k & 3][p[i + k]];
      i += literals;
      if (!found) continue;
    }
#endif
    const size_t max = std::min(kMaxMatch, end - i);
    size_t best = 0;
    int which = 0;
    if (pixel && i >= pixel) best = matchLength(p + i, p + i - pixel, max);
    if (row && i >= row && best < max)
      if (const size_t len = matchLength(p + i, p + i - row, max); len > best) best = len, which = 1;
    if (best >= kMinMatch) {
      *token++ = kMatch | uint32_t(best) << 1 | uint32_t(which);
      ++t.litFreq[257 + kLengthCode[best]];
      ++t.uses[which];
      i += best;
    } else {
      *token++ = p[i];
      ++t.litFreq[p[i]];
      ++i;
    }
  }
  for (const auto& counts : runFreq)
    for (int v = 0; v < 256; ++v) t.litFreq[v] += counts[v];
  ++t.litFreq[kEndOfBlock];
  t.tokens = std::span(first, token);
}

// A dynamic block's three codes (3.2.7): literals and lengths, distances,
// and the code its code lengths are sent in.
struct BlockCodes {
  Code lit, dist, lengths;
  int nLit = kLiterals, nDist = kDistances, nLength = kCodeLengths;
  std::span<const LengthSymbol> symbols;

  BlockCodes(Tokens& t, std::array<uint32_t, kDistances>& distFreq) {
    lit.build(t.litFreq, 15);
    dist.build(distFreq, 15);
    while (nLit > 257 && !lit.length[nLit - 1]) --nLit;
    while (nDist > 1 && !dist.length[nDist - 1]) --nDist;
    std::array<uint8_t, kLiterals + kDistances> all;
    std::copy_n(lit.length.begin(), nLit, all.begin());
    std::copy_n(dist.length.begin(), nDist, all.begin() + nLit);
    symbols = lengthSymbols(all.data(), nLit + nDist);
    std::array<uint32_t, kCodeLengths> freq{};
    for (const LengthSymbol& s : symbols) ++freq[s.symbol];
    lengths.build(freq, 7);
    while (nLength > 4 && !lengths.length[kCodeLengthOrder[nLength - 1]]) --nLength;
  }

  void writeHeader(BitSink& sink, bool last) const {
    sink.put(last ? 1 : 0, 1);
    sink.put(2, 2);  // dynamic Huffman codes
    sink.put(uint32_t(nLit - 257), 5);
    sink.put(uint32_t(nDist - 1), 5);
    sink.put(uint32_t(nLength - 4), 4);
    for (int k = 0; k < nLength; ++k) sink.put(lengths.length[kCodeLengthOrder[k]], 3);
    for (const LengthSymbol& s : symbols) {
      sink.put(lengths.bits[s.symbol], lengths.length[s.symbol]);
      if (s.symbol >= 16) sink.put(s.extra, s.symbol == 16 ? 2 : s.symbol == 17 ? 3 : 7);
    }
  }
};

}  // namespace

void RowDeflater::block(std::span<const uint8_t> data, size_t begin, size_t pixel, size_t row, bool last,
                        std::vector<unsigned char>& out) {
  const size_t distance[2] = {pixel <= kWindow ? pixel : 0, row <= kWindow ? row : 0};
  Tokens t;
  tokenize(data, begin, distance, t);
  int distanceCodes[2];
  std::array<uint32_t, kDistances> distFreq{};
  for (int w = 0; w < 2; ++w) distFreq[distanceCodes[w] = distanceCode(std::max<size_t>(distance[w], 1))] += t.uses[w];
  const BlockCodes codes(t, distFreq);

  // At most 15 + 5 + 15 + 13 bits a token of at least one byte, the
  // header's few hundred bytes and the sink's eight: into scratch memory
  // that is not zero-filled for every block.
  thread_local std::vector<unsigned char> scratch;
  scratch.resize(std::max(scratch.size(), 2 * (data.size() - begin) + 1024));
  BitSink sink{bits_, count_, scratch.data()};
  codes.writeHeader(sink, last);
  uint32_t distBits[2], distLength[2];
  for (int w = 0; w < 2; ++w) {
    const int c = distanceCodes[w];
    // The code, then the extra bits above the code's base.
    const uint32_t extra = uint32_t(std::max<size_t>(distance[w], 1) - kDistanceBase[c]);
    distBits[w] = codes.dist.bits[c] | extra << codes.dist.length[c];
    distLength[w] = codes.dist.length[c] + kDistanceExtra[c];
  }
  const Code& lit = codes.lit;
  for (const uint32_t token : t.tokens) {
    if (!(token & kMatch)) {
      sink.put(lit.bits[token], lit.length[token]);
      continue;
    }
    const size_t len = (token & ~kMatch) >> 1;
    const int c = kLengthCode[len], symbol = 257 + c;
    const uint32_t extra = uint32_t(len - kLengthBase[c]);
    sink.put(lit.bits[symbol] | extra << lit.length[symbol], lit.length[symbol] + kLengthExtra[c]);
    sink.put(distBits[token & 1u], int(distLength[token & 1u]));
  }
  sink.put(lit.bits[kEndOfBlock], lit.length[kEndOfBlock]);
  // Whole bytes are out; the last block's final bits padded to a byte.
  if (last && sink.count > 0) {
    *sink.at++ = uint8_t(sink.bits);
    sink.bits = 0;
    sink.count = 0;
  }
  bits_ = sink.bits;
  count_ = sink.count;
  out.insert(out.end(), scratch.data(), sink.at);
}

}  // namespace mvr
