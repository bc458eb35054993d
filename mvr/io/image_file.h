#pragma once
// Image files through OpenImageIO.
#include <string>

#include "mvr/image.h"

namespace mvr {

// zlib level of PNG files unless a caller says otherwise. Measured on
// 1000 views of the 143K teacup at 160x140 (docs/BENCHMARKS.md): level 1
// deflates 4x faster than zlib's default 6 for files 25% larger, and
// encoding is what a whole render waits for.
inline constexpr int kDefaultPngCompression = 1;

// Writes png or tiff (8 or 16 bits per channel; float images are
// quantised) or exr (32-bit float; bits is ignored); pngCompression: zlib
// level 0-9 of png files. Writes to a temporary name and renames, so a
// failed write leaves nothing behind.
void writeImage(const Image& image, const std::string& path, int bits = 8,
                int pngCompression = kDefaultPngCompression);
Image readImage(const std::string& path);  // 4 channels, U8 or F32

}  // namespace mvr
