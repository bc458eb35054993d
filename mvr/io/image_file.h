#pragma once
// Image files through OpenImageIO.
#include <string>

#include "mvr/image.h"

namespace mvr {

// Writes png or tiff (8 or 16 bits per channel; float images are
// quantised) or exr (32-bit float; bits is ignored). Writes to a temporary
// name and renames, so a failed write leaves nothing behind.
void writeImage(const Image& image, const std::string& path, int bits = 8);
Image readImage(const std::string& path);  // 4 channels, U8 or F32

}  // namespace mvr
