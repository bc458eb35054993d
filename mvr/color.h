#pragma once
// The sRGB transfer function (IEC 61966-2-1). Renderers compute in linear
// light; 8- and 16-bit files and displays expect sRGB-encoded values, and
// quantising linear values to 8 bits first would leave the dark tones a
// handful of levels (linear 1/255 is sRGB 13/255). So 8-bit sRGB output
// is encoded from the full-precision value, as GL's sRGB render targets do.
#include <cstdint>

namespace mvr {

float srgbEncode(float linear);   // [0, 1] -> [0, 1]; clamped
float srgbDecode(float encoded);  // [0, 1] -> [0, 1]; clamped
// round(srgbEncode(linear) * 255) exactly, without a pow per call.
uint8_t srgb8(float linear);
// srgbDecode(value / 255).
float linearOfSrgb8(uint8_t value);

}  // namespace mvr
