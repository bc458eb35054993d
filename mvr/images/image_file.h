#pragma once
// Image files through OpenImageIO.
#include <string>
#include <utility>
#include <vector>

#include "mvr/image.h"
#include "mvr/images/image_encoding.h"

namespace mvr {

// Throws mvr::Error naming the option (--bits, --codec, --compression)
// when the encoding is not one `format` (png, exr, tiff) can store.
void checkEncoding(const std::string& format, const ImageEncoding& encoding);

// Writes an image with the format its extension names. Encodes in memory,
// then writes through writeFileAtomically: a failed write leaves nothing
// behind and names the system's reason.
void writeImage(const Image& image, const std::string& path, const ImageEncoding& encoding = {});
// 4 channels: F32 for float files; 8-bit files as Srgb8, or U8 when they
// say they are linear.
Image readImage(const std::string& path);

// A depth map as a 32-bit exr file with one channel, Z (its codec from
// encoding.codec if it is an exr codec, else zip), written as writeImage
// writes.
void writeDepthImage(const DepthImage& depth, const std::string& path, const ImageEncoding& encoding = {});
// The first channel of any file OpenImageIO reads (exr Z, PFM, ...).
DepthImage readDepthImage(const std::string& path);

// A string attribute of a file as OpenImageIO reads it ("" when absent).
std::string readImageAttribute(const std::string& path, const std::string& name);

// What a file stores, as writeImage describes it (bits per channel, the
// codec OpenImageIO reports, "" for png, and whether it says sRGB).
ImageEncoding readImageEncoding(const std::string& path);

}  // namespace mvr
