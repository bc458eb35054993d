#include "mvr/color.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace mvr {
namespace detail {

Srgb8Table::Srgb8Table() {
  for (int b = 0; b < 255; ++b) upper[b] = srgbDecode((float(b) + 0.5f) / 255.0f);
  upper[255] = INFINITY;
  for (int k = 0; k <= kBuckets; ++k) {
    const float v = float(k) / kBuckets;
    start[k] = uint8_t(std::upper_bound(upper.begin(), upper.end(), v) - upper.begin());
  }
  for (int b = 0; b < 256; ++b) decoded[b] = srgbDecode(float(b) / 255.0f);
}

const Srgb8Table& srgb8Table() {
  static const Srgb8Table t;
  return t;
}

}  // namespace detail

float srgbEncode(float linear) {
  if (!(linear > 0.0f)) return 0.0f;  // NaN too
  if (linear >= 1.0f) return 1.0f;
  return linear <= 0.0031308f ? 12.92f * linear
                              : std::min(1.0f, 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f);
}

float srgbDecode(float encoded) {
  const float v = std::clamp(encoded, 0.0f, 1.0f);
  return v <= 0.04045f ? v / 12.92f : std::min(1.0f, std::pow((v + 0.055f) / 1.055f, 2.4f));
}

float linearOfSrgb8(uint8_t value) { return detail::srgb8Table().decoded[value]; }

}  // namespace mvr
