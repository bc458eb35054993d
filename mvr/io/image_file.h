#pragma once
// Image files through OpenImageIO.
#include <string>
#include <utility>
#include <vector>

#include "mvr/image.h"

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
// own encoder (mvr/io/exr_depth.h), with no OpenImageIO module loaded.
inline bool ownsDepthCodec(const std::string& codec) { return codec.empty() || codec == "zip" || codec == "none"; }
// 32 (float) for exr, 8 for png and tiff.
inline int defaultBits(const std::string& format) { return format == "exr" ? 32 : 8; }
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
