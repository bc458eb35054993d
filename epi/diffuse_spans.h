#pragma once
// The CPU span back end's fill of untextured, diffuse slices
// (epi/span_rasterizer.cpp), the common case: a row's pixels four at a
// time, each lane doing the general path's arithmetic (pstDepth,
// pstColor), so the bytes are the same; and the 8-bit encoding, which was
// half of the fill's time, mostly replaced by what a slice's colour being
// monotone allows (SliceCodes). GCC and Clang vector extensions: SSE on
// x86-64, NEON on ARM.
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <functional>

#include <glm/glm.hpp>

#include "epi/pst.h"

// Whether the fill is compiled a second time for x86-64-v2 (SSE4.1: ceil
// and a lane select an instruction each), run where the CPU has it. v2
// has no FMA, so both compute the same bytes.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define MVR_SPAN_V2 1
#else
#define MVR_SPAN_V2 0
#endif

namespace mvr::spans {

// int(std::ceil(v)) for |v| up to 1e9, clamped beyond (an extrapolated
// corner can lie far outside). Without SSE4.1 the compiler builds ceil
// from masks and magic numbers; rows of a PST cost two of them each, and
// at 160x140 x 1000 views the rows, not the pixels, are the fill's work.
inline int ceilToInt(float v) {
  v = std::clamp(v, -1e9f, 1e9f);
  const int t = int(v);  // towards zero
  return t + (float(t) < v);
}

// Four floats or ints, one per pixel or row (GCC and Clang vector
// extensions: SSE on x86-64, NEON on ARM; each lane's arithmetic is IEEE
// single precision, as the scalar code's).
using F4 = float __attribute__((vector_size(16)));
using I4 = int32_t __attribute__((vector_size(16)));

// ceilToInt in each lane.
inline I4 ceilToInt(F4 v) {
  v = v < -1e9f ? F4{} - 1e9f : v;
  v = 1e9f < v ? F4{} + 1e9f : v;
  const I4 t = __builtin_convertvector(v, I4);  // towards zero
  return t - (__builtin_convertvector(t, F4) < v);  // true is -1
}

// What plainRun needs of a diffuse slice, as pstColor and pstDepth use it.
struct PlainSlice {
  PlainSlice(const Pst& pst, bool front)
      : depth0(pst.e0.depth), depthStep(pst.e1.depth - pst.e0.depth), invW0(pst.e0.invW),
        invWStep(pst.e1.invW - pst.e0.invW), color0(front ? pst.e0.frontOverW : pst.e0.backOverW),
        colorStep((front ? pst.e1.frontOverW : pst.e1.backOverW) - color0) {}
  float depth0, depthStep, invW0, invWStep;
  glm::vec3 color0, colorStep;
};

// How plainRun encodes a diffuse slice's 8-bit pixels. Its colour
// (a + b u) / (c + d u), c + d u > 0, is monotone in u, so each
// channel's code lies between those of the slice's ends, widened by the
// rounding any u may add: [lo, hi]. Flat: lo == hi in every channel,
// one pixel for all (many slices of a finely tessellated mesh). Count:
// a few codes per channel, so a pixel's code is lo plus the thresholds
// above lo it reaches, counted four pixels at a time. Encode: one
// encoding per pixel. Encoding was the fill's largest cost.
struct SliceCodes {
  enum class Kind { Encode, Flat, Count } kind = Kind::Encode;
  std::array<uint8_t, 4> pixel{};            // Flat: every pixel's bytes
  std::array<int32_t, 3> base{}, steps{};      // Count: per channel lo, hi - lo
  std::array<const float*, 3> thresholds{};  // Count: the steps' thresholds
};
inline constexpr int kMaxSteps = 8;  // more thresholds than this cost more than encoding

template <class Encode>
SliceCodes sliceCodes(const Pst& pst, bool front, Encode& encode, const std::array<float, 255>& thresholds) {
  const glm::vec3 a = pstColor(pst, front, 0.0f), b = pstColor(pst, front, 1.0f);
  const glm::vec3 c0 = front ? pst.e0.frontOverW : pst.e0.backOverW;
  const glm::vec3 dc = (front ? pst.e1.frontOverW : pst.e1.backOverW) - c0;
  const float invW0 = pst.e0.invW, dInvW = pst.e1.invW - pst.e0.invW;
  const float minInvW = std::min(invW0, pst.e1.invW);
  if (!(minInvW > 0.0f)) return {};
  const glm::vec3 top = glm::max(glm::abs(a), glm::abs(b));
  // A few ulps of numerator and denominator, as absolute errors of the
  // quotient (they cancel in neither), with room to spare.
  const glm::vec3 margin =
      2e-6f * ((glm::abs(c0) + glm::abs(dc) + top * (std::abs(invW0) + std::abs(dInvW))) / minInvW + top);
  std::array<uint8_t, 4> lo, hi;
  encode(lo.data(), glm::clamp(glm::min(a, b) - margin, 0.0f, 1.0f));
  encode(hi.data(), glm::clamp(glm::max(a, b) + margin, 0.0f, 1.0f));
  SliceCodes codes;
  codes.pixel = lo;
  if (lo == hi) {
    codes.kind = SliceCodes::Kind::Flat;
    return codes;
  }
  for (int k = 0; k < 3; ++k) {
    codes.base[k] = lo[k], codes.steps[k] = hi[k] - lo[k];
    if (codes.steps[k] > kMaxSteps) return codes;
    codes.thresholds[k] = thresholds.data() + lo[k];
  }
  codes.kind = SliceCodes::Kind::Count;
  return codes;
}

// The thresholds of the 8-bit encoding: code(v) is the number of
// thresholds at most v, for v in [0, 1]. Found by bisection over the
// floats with the encoder itself, so counting reproduces it exactly
// (it is monotone: a rounded monotone curve).
inline std::array<float, 255> thresholdsOf(const std::function<int(float)>& code) {
  std::array<float, 255> thresholds{};
  for (int t = 0; t < 255; ++t) {
    // The least v with code(v) > t; positive floats order as their bits.
    uint32_t below = std::bit_cast<uint32_t>(0.0f), at = std::bit_cast<uint32_t>(1.0f);
    while (at - below > 1) {
      const uint32_t mid = below + (at - below) / 2;
      (code(std::bit_cast<float>(mid)) > t ? at : below) = mid;
    }
    thresholds[t] = std::bit_cast<float>(at);
  }
  return thresholds;
}

inline bool any(I4 lanes) {
  uint64_t halves[2];
  std::memcpy(halves, &lanes, sizeof halves);
  return (halves[0] | halves[1]) != 0;
}

// 8-bit pixels x .. x + 3 of a row of w: the passing lanes' replace
// those in the row, one blend when all four lie in it.
inline void putPixels(uint8_t* row, int x, int w, I4 pixels, I4 pass) {
  uint8_t* at = row + size_t(x) * 4;
  if (x + 4 <= w) {
    I4 old;
    std::memcpy(&old, at, sizeof old);
    const I4 blend = pass ? pixels : old;
    std::memcpy(at, &blend, sizeof blend);
    return;
  }
  for (int k = 0; k < 4; ++k)
    if (pass[k]) {
      const int32_t p = pixels[k];
      std::memcpy(at + 4 * k, &p, 4);
    }
}

// Pixels [x0, x1) of one row of a diffuse slice, four at a time: the
// general path's u, depth test and pstColor in each lane, encoded as
// `codes` says. `dz` may be read and written up to 3 floats past x1
// (fillEpi pads the buffer); those lanes keep their values.
template <class Encode>
[[gnu::always_inline]] inline void plainRun(const PlainSlice& s, const SliceCodes& codes, float* dz, uint8_t* row,
                                            int w, size_t pixelBytes, int x0, int x1, float xa, float width,
                                            Encode& encode) {
  static_assert(std::endian::native == std::endian::little, "counted pixels are packed as R | G << 8 | ...");
  const I4 lanes = {0, 1, 2, 3};
  for (int x = x0; x < x1; x += 4) {
    F4 u = (__builtin_convertvector(x + lanes, F4) + 0.5f - xa) / width;
    u = u < 0.0f ? F4{} : u;  // std::clamp(u, 0, 1)
    u = 1.0f < u ? F4{} + 1.0f : u;
    const F4 z = s.depth0 + s.depthStep * u;
    F4 old;
    std::memcpy(&old, dz + x, sizeof old);
    const I4 pass = (z > old) & (lanes < x1 - x);
    if (!any(pass)) continue;
    const F4 kept = pass ? z : old;
    std::memcpy(dz + x, &kept, sizeof kept);
    if (codes.kind == SliceCodes::Kind::Flat) {
      putPixels(row, x, w, I4{} + std::bit_cast<int32_t>(codes.pixel), pass);
      continue;
    }
    const F4 invW = s.invW0 + s.invWStep * u;
    F4 c[3];
    for (int k = 0; k < 3; ++k) {
      c[k] = (s.color0[k] + s.colorStep[k] * u) / invW;
      c[k] = c[k] < 0.0f ? F4{} : c[k];  // glm::clamp(c, 0, 1); float pixels keep HDR values above 1
      if (pixelBytes == 4) c[k] = c[k] > 1.0f ? F4{} + 1.0f : c[k];
    }
    if (codes.kind == SliceCodes::Kind::Count) {
      I4 pixels = I4{} + int32_t(0xff000000u);  // alpha 255
      for (int k = 0; k < 3; ++k) {
        I4 code = I4{} + codes.base[k];
        for (int j = 0; j < codes.steps[k]; ++j) code -= c[k] >= codes.thresholds[k][j];  // true is -1
        pixels |= code << (8 * k);
      }
      putPixels(row, x, w, pixels, pass);
      continue;
    }
    for (int k = 0; k < 4; ++k)
      if (pass[k]) encode(row + size_t(x + k) * pixelBytes, glm::vec3(c[0][k], c[1][k], c[2][k]));
  }
}

}  // namespace mvr::spans
