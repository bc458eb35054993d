#include "mvr/color.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace mvr {
namespace {

// Quantisation thresholds: srgb8(v) is the number of byte boundaries at or
// below v. A coarse table gives the first candidate, a short walk the rest
// (the steepest part of the curve, near 0, spans ~3.2 levels per bucket).
struct Srgb8Table {
  static constexpr int kBuckets = 1024;
  std::array<float, 255> upper{};  // linear value where byte b rounds up to b + 1
  std::array<uint8_t, kBuckets + 1> start{};
  std::array<float, 256> decoded{};

  Srgb8Table() {
    for (int b = 0; b < 255; ++b) upper[b] = srgbDecode((float(b) + 0.5f) / 255.0f);
    for (int k = 0; k <= kBuckets; ++k) {
      const float v = float(k) / kBuckets;
      start[k] = uint8_t(std::upper_bound(upper.begin(), upper.end(), v) - upper.begin());
    }
    for (int b = 0; b < 256; ++b) decoded[b] = srgbDecode(float(b) / 255.0f);
  }
};

const Srgb8Table& table() {
  static const Srgb8Table t;
  return t;
}

}  // namespace

float srgbEncode(float linear) {
  const float v = std::clamp(linear, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

float srgbDecode(float encoded) {
  const float v = std::clamp(encoded, 0.0f, 1.0f);
  return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f);
}

uint8_t srgb8(float linear) {
  const Srgb8Table& t = table();
  if (!(linear > 0.0f)) return 0;  // NaN too
  if (linear >= 1.0f) return 255;
  int b = t.start[int(linear * Srgb8Table::kBuckets)];
  while (b < 255 && linear >= t.upper[b]) ++b;
  return uint8_t(b);
}

float linearOfSrgb8(uint8_t value) { return table().decoded[value]; }

}  // namespace mvr
