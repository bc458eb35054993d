#include "mvr/images/adler32.h"

#include <algorithm>

#ifdef __SSE2__
#include <emmintrin.h>
#endif

namespace mvr {
namespace {

constexpr uint32_t kBase = 65521;
#ifdef __SSE2__
// Bytes summed between reductions: every lane's sum stays well inside 32
// bits (the weighted sums grow by at most 255 x 63 a lane a step), and
// the 64-bit tallies below cannot overflow.
constexpr size_t kBlock = size_t(32) << 9;

uint64_t lanes64(__m128i v) {
  alignas(16) uint64_t x[2];
  _mm_store_si128(reinterpret_cast<__m128i*>(x), v);
  return x[0] + x[1];
}

uint64_t lanes32(__m128i v) {
  alignas(16) uint32_t x[4];
  _mm_store_si128(reinterpret_cast<__m128i*>(x), v);
  return uint64_t(x[0]) + x[1] + x[2] + x[3];
}

#endif

}  // namespace

// Over n bytes d[0..n) from (a, b): a' = a + sum d[i] and
// b' = b + n a + sum (n - i) d[i]. Taken 32 bytes at a time, b' adds for
// each step 32 times the bytes summed in the steps before it and the
// step's own bytes weighted 32 down to 1.
uint32_t adler32Update(uint32_t adler, std::span<const uint8_t> bytes) {
  uint64_t a = adler & 0xffff, b = adler >> 16;
  const uint8_t* p = bytes.data();
  size_t n = bytes.size();
#ifdef __SSE2__
  const __m128i zero = _mm_setzero_si128();
  const __m128i w0 = _mm_setr_epi16(32, 31, 30, 29, 28, 27, 26, 25), w1 = _mm_setr_epi16(24, 23, 22, 21, 20, 19, 18, 17);
  const __m128i w2 = _mm_setr_epi16(16, 15, 14, 13, 12, 11, 10, 9), w3 = _mm_setr_epi16(8, 7, 6, 5, 4, 3, 2, 1);
  while (n >= 32) {
    const size_t steps = std::min(n, kBlock) / 32;
    __m128i sum = zero, before = zero, weighted = zero;  // 64-, 64- and 32-bit lanes
    for (size_t s = 0; s < steps; ++s, p += 32) {
      const __m128i lo = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
      const __m128i hi = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p + 16));
      before = _mm_add_epi64(before, sum);
      sum = _mm_add_epi64(sum, _mm_add_epi64(_mm_sad_epu8(lo, zero), _mm_sad_epu8(hi, zero)));
      weighted = _mm_add_epi32(weighted, _mm_madd_epi16(_mm_unpacklo_epi8(lo, zero), w0));
      weighted = _mm_add_epi32(weighted, _mm_madd_epi16(_mm_unpackhi_epi8(lo, zero), w1));
      weighted = _mm_add_epi32(weighted, _mm_madd_epi16(_mm_unpacklo_epi8(hi, zero), w2));
      weighted = _mm_add_epi32(weighted, _mm_madd_epi16(_mm_unpackhi_epi8(hi, zero), w3));
    }
    const uint64_t taken = steps * 32;
    b = (b + taken * a + 32 * lanes64(before) + lanes32(weighted)) % kBase;
    a = (a + lanes64(sum)) % kBase;
    n -= taken;
  }
#endif
  // The rest a byte at a time (under 32 bytes with SSE2), reduced often
  // enough that b cannot overflow.
  while (n > 0) {
    const size_t run = std::min<size_t>(n, 5552);
    for (size_t k = 0; k < run; ++k, ++p) a += *p, b += a;
    a %= kBase, b %= kBase, n -= run;
  }
  return uint32_t(b << 16 | a);
}

}  // namespace mvr
