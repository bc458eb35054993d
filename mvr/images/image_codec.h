#pragma once
// OpenImageIO's encoders and decoders, in a module (mvr_oiio) loaded at run
// time instead of linked: Debian's OpenImageIO brings about 260 libraries
// (OpenCV, GDAL, FFmpeg, DCMTK ...), and loading them took 0.5 s at every
// start of every program, before main ran, whether it wrote an image or
// not. Commands that will write images start the load on a background
// thread (preloadImageCodec), so it overlaps scene loading and rendering.
//
// The module is found at MVR_IMAGE_CODEC when set, else at
// ../lib/libmvr_oiio.so beside the running program (build/bin -> build/lib).
#include <string>
#include <vector>

#include "mvr/image.h"
#include "mvr/images/image_encoding.h"

namespace mvr {

// What the module exports. Each function returns "" or the reason it failed.
struct ImageCodec {
  // pixels as the file stores them (bytes, or float values already encoded
  // where the file says sRGB); format png, exr or tiff; srgbTag: the PNG
  // says sRGB (else linear, gAMA 1.0).
  std::string (*encode)(const Image& pixels, const std::string& format, const ImageEncoding& encoding,
                        bool srgbTag, std::vector<unsigned char>& out);
  // One float channel named Z, as an exr file of encoding.codec (32-bit).
  std::string (*encodeDepth)(const DepthImage& depth, const ImageEncoding& encoding,
                             std::vector<unsigned char>& out);
  // Any file OpenImageIO reads, widened to RGBA: F32 for float files; 8-bit
  // files as Srgb8, or U8 when they say they are linear.
  std::string (*decode)(const std::string& path, Image& out);
  // What a file says of its storage: bits per channel, its
  // "compression" attribute, and whether it says it is linear.
  std::string (*describe)(const std::string& path, int& bits, std::string& compression, bool& linear);
  // A string attribute of the file ("" when absent).
  std::string (*attribute)(const std::string& path, const std::string& name, std::string& value);
};

// The codec: loaded now, or when a preload is running, once it is done.
// Throws mvr::Error naming the module when it cannot be loaded.
const ImageCodec& imageCodec();
// Starts loading the module on a background thread; returns at once.
void preloadImageCodec();
// Seconds the module's load took (0 before it is loaded).
double imageCodecLoadSeconds();

}  // namespace mvr

// The module's one exported symbol.
extern "C" const mvr::ImageCodec* mvrImageCodec();
