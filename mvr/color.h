#pragma once
// The sRGB transfer function (IEC 61966-2-1). Renderers compute in linear
// light; 8- and 16-bit files and displays expect sRGB-encoded values, and
// quantising linear values to 8 bits first would leave the dark tones a
// handful of levels (linear 1/255 is sRGB 13/255). So 8-bit sRGB output
// is encoded from the full-precision value, as GL's sRGB render targets do.
#include <array>
#include <cstdint>

namespace mvr {

float srgbEncode(float linear);   // [0, 1] -> [0, 1]; clamped
float srgbDecode(float encoded);  // [0, 1] -> [0, 1]; clamped
// srgbDecode(value / 255).
float linearOfSrgb8(uint8_t value);

namespace detail {
// Quantisation thresholds: upper[b] is the linear value where byte b
// rounds up to b + 1. start[k] is the byte at k / kBuckets; with 4096
// buckets the steepest part of the curve (3295 levels per unit, near 0)
// puts at most one threshold in a bucket, so one comparison finishes.
struct Srgb8Table {
  static constexpr int kBuckets = 4096;
  std::array<float, 256> upper{};  // upper[255] = +inf
  std::array<uint8_t, kBuckets + 1> start{};
  std::array<float, 256> decoded{};
  Srgb8Table();
};
const Srgb8Table& srgb8Table();
}  // namespace detail

// round(srgbEncode(linear) * 255), exactly: a table and one comparison, no
// pow. Hold one where it is called per pixel (the CPU rasterizer): it
// keeps the table at hand.
class Srgb8Encoder {
 public:
  Srgb8Encoder() : t_(detail::srgb8Table()) {}
  uint8_t operator()(float linear) const {
    if (!(linear > 0.0f)) return 0;  // NaN too
    if (linear >= 1.0f) return 255;
    const int b = t_.start[int(linear * detail::Srgb8Table::kBuckets)];
    return uint8_t(b + (linear >= t_.upper[b]));
  }

 private:
  const detail::Srgb8Table& t_;
};

inline uint8_t srgb8(float linear) { return Srgb8Encoder()(linear); }

}  // namespace mvr
