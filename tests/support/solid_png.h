#pragma once
// A one-colour texture file for loader tests: whether a texture came
// through shows in a rendered pixel's colour.
#include <cstdint>
#include <cstring>
#include <filesystem>

#include "mvr/image.h"
#include "mvr/images/image_file.h"

namespace mvr::test {

// The texel of kRed textures: sRGB (200, 40, 20), opaque.
inline constexpr uint8_t kRed[4] = {200, 40, 20, 255};

// A side x side PNG of kRed texels.
inline void writeRedPng(const std::filesystem::path& path, int side) {
  Image texels(side, side, PixelType::Srgb8);
  for (size_t i = 0; i < size_t(side) * side; ++i) std::memcpy(&texels.bytes[4 * i], kRed, 4);
  writeImage(texels, path.string());
}

}  // namespace mvr::test
