#pragma once
// How an image file stores its pixels: what image_file writes with and
// what the OpenImageIO module (mvr/images/image_codec.h) encodes to.
#include <string>
#include <utility>
#include <vector>

namespace mvr {

// zlib level of PNG files unless a caller says otherwise. Measured on
// 1000 views of the 143K teacup at 160x140 (docs/BENCHMARKS.md): level 1
// deflates 4x faster than zlib's default 6 for files 25% larger, and
// encoding is what a whole render waits for.
inline constexpr int kDefaultPngCompression = 1;

// How a file stores its pixels. png: 8 or 16 bits, zlib level pngLevel.
// tiff: 8 or 16 bits, codec none, lzw or zip. exr: 16 (half) or 32 (float)
// bits, codec none, rle, zip, zips, piz, pxr24, b44, dwaa or dwab. Float
// images are quantised for 8 and 16-bit integer files. An empty codec is
// the format's default (defaultCodec). srgb: float images written to png
// and tiff files are sRGB-encoded before quantising, and tagged sRGB;
// otherwise written and tagged linear. Byte images are written as stored
// and tagged by their type (U8 linear, Srgb8 sRGB); exr is always linear.
struct ImageEncoding {
  int bits = 8;
  int pngLevel = kDefaultPngCompression;
  std::string codec;
  bool srgb = true;
  // Metadata written with the pixels, as OpenImageIO names it (e.g.
  // "Exif:UserComment"): string attributes.
  std::vector<std::pair<std::string, std::string>> attributes = {};
};

// "" for png, "zip" for tiff and exr.
inline std::string defaultCodec(const std::string& format) { return format == "png" ? "" : "zip"; }
// Depth maps of these codecs (the default zip, and none) are written by our
// own encoder (mvr/images/exr_depth.h), with no OpenImageIO module loaded.
inline bool ownsDepthCodec(const std::string& codec) { return codec.empty() || codec == "zip" || codec == "none"; }
// 32 (float) for exr, 8 for png and tiff.
inline int defaultBits(const std::string& format) { return format == "exr" ? 32 : 8; }

}  // namespace mvr
