#pragma once
// RGBA images, 8-bit or float, rows top first (file IO: mvr/images/image_file.h).
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "mvr/large_pages.h"

namespace mvr {

// U8 and F32 hold linear values; Srgb8 holds sRGB-encoded colour (alpha
// linear), what 8-bit files and displays expect (mvr/color.h).
enum class PixelType { U8, Srgb8, F32 };

inline bool isByteType(PixelType t) { return t != PixelType::F32; }

// A frame-sized image's pixels on huge pages (mvr/large_pages.h).
using ImageBytes = std::vector<uint8_t, LargePageAllocator<uint8_t>>;

struct Image {
  int width = 0, height = 0;
  PixelType type = PixelType::U8;
  ImageBytes bytes;  // width * height * 4 * bytesPerChannel

  Image() = default;
  Image(int w, int h, PixelType t)
      : width(w), height(h), type(t), bytes(size_t(w) * h * 4 * channelBytes(t)) {}
  static size_t channelBytes(PixelType t) { return isByteType(t) ? 1 : 4; }
  size_t rowBytes() const { return size_t(width) * 4 * channelBytes(type); }
  uint8_t* row(int y) { return bytes.data() + y * rowBytes(); }
  const uint8_t* row(int y) const { return bytes.data() + y * rowBytes(); }
  // Stored channel values scaled to [0, 1] (sRGB-encoded for Srgb8).
  glm::vec4 pixel(int x, int y) const;
  // Linear-light values: Srgb8 colour decoded.
  glm::vec4 linear(int x, int y) const;
  // Stores linear-light values: quantised (byte types, clamped to [0, 1])
  // and sRGB-encoded for Srgb8.
  void setLinear(int x, int y, const glm::vec4& v);
};

// Rows of pixels in memory someone else owns (a run of an image's rows, a
// sink's): what a fill writes into when it writes in place.
struct PixelRows {
  uint8_t* data = nullptr;
  int width = 0, height = 0;
  PixelType type = PixelType::U8;

  PixelRows() = default;
  PixelRows(uint8_t* d, int w, int h, PixelType t) : data(d), width(w), height(h), type(t) {}
  explicit PixelRows(Image& image) : PixelRows(image.bytes.data(), image.width, image.height, image.type) {}
  size_t rowBytes() const { return size_t(width) * 4 * Image::channelBytes(type); }
  size_t bytes() const { return rowBytes() * size_t(height); }
  uint8_t* row(int y) const { return data + size_t(y) * rowBytes(); }
};

// One float per pixel, rows top first: a depth map (mvr/depth.h).
struct DepthImage {
  int width = 0, height = 0;
  std::vector<float> values;  // width * height

  DepthImage() = default;
  DepthImage(int w, int h) : width(w), height(h), values(size_t(w) * h, 0.0f) {}
  float& at(int x, int y) { return values[size_t(y) * width + x]; }
  float at(int x, int y) const { return values[size_t(y) * width + x]; }
};

// One RGBA8 pixel as GL_SRGB8_ALPHA8 stores it (colour sRGB-encoded, alpha
// linear), from and to linear light; values outside [0, 1] clamp.
glm::vec4 decodeSrgb8(const uint8_t* rgba);
void encodeSrgb8(const glm::vec4& linear, uint8_t* rgba);

// The rectangle (x, y, w, h) of src resampled bilinearly (edges clamped,
// in linear light) to width x height, as sRGB-encoded RGBA8 (alpha
// linear): what textures are stored as, decoded by GL's sRGB textures and
// by the CPU samplers. bottomUp: output row 0 is the rectangle's bottom
// row, as GL's 2D texture convention wants.
std::vector<uint8_t> resampleSrgb8(const Image& src, glm::ivec4 rect, int width, int height,
                                   bool bottomUp);

}  // namespace mvr
