#include "mvr/images/image_file.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <vector>

#include "mvr/color.h"
#include "mvr/error.h"
#include "mvr/files/atomic_file.h"
#include "mvr/images/exr_depth.h"
#include "mvr/images/image_codec.h"
#include "mvr/images/png_encoder.h"

namespace mvr {

namespace {

const std::vector<std::string>& codecs(const std::string& format) {
  static const std::vector<std::string> none, tiff{"none", "lzw", "zip"},
      exr{"none", "rle", "zip", "zips", "piz", "pxr24", "b44", "dwaa", "dwab"};
  return format == "tiff" ? tiff : format == "exr" ? exr : none;
}

std::string formatOf(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  if (!ext.empty()) ext.erase(0, 1);
  return ext == "tif" ? "tiff" : ext;
}

}  // namespace

void checkEncoding(const std::string& format, const ImageEncoding& e) {
  if (format == "exr") {
    if (e.bits != 16 && e.bits != 32) fail("--bits", "exr stores 16 (half) or 32 (float) bits");
  } else if (e.bits != 8 && e.bits != 16) {
    fail("--bits", format + " stores 8 or 16 bits");
  }
  if (e.pngLevel < 0 || e.pngLevel > 9) fail("--compression", "expected 0..9");
  const auto& allowed = codecs(format);
  if (e.codec.empty() || std::find(allowed.begin(), allowed.end(), e.codec) != allowed.end()) return;
  if (allowed.empty()) fail("--codec", format + " has no codec choice (its level is --compression)");
  std::string list;
  for (const std::string& c : allowed) list += (list.empty() ? "" : ", ") + c;
  fail("--codec", "'" + e.codec + "' is not a " + format + " codec (" + list + ")");
}

namespace {

// The float image a file of `encoding` stores: sRGB-encoded colour for
// integer files that say sRGB, linear otherwise (Srgb8 images decoded).
Image floatFor(const Image& image, bool encode) {
  Image out(image.width, image.height, PixelType::F32);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      glm::vec4 v = image.linear(x, y);
      if (encode) v = {srgbEncode(v.r), srgbEncode(v.g), srgbEncode(v.b), v.a};
      out.setLinear(x, y, v);
    }
  return out;
}

// encode: the pixels are linear floats the file stores sRGB-encoded.
void encodePng(const Image& pixels, const ImageEncoding& e, bool srgb, bool encode, std::vector<unsigned char>& out) {
  PngEncoder png({pixels.width, pixels.height, e.bits, e.pngLevel, srgb, e.attributes}, out);
  std::vector<uint8_t> room;
  for (int y = 0; y < pixels.height; ++y) png.addRow(pngRow(pixels, y, e.bits, encode, room));
}

}  // namespace

void writeImage(const Image& image, const std::string& path, const ImageEncoding& encoding) {
  const std::string format = formatOf(path);
  if (format != "png" && format != "exr" && format != "tiff") fail(path, "no image writer for this extension");
  checkEncoding(format, encoding);
  // Byte images go out as stored when the file holds bytes; everything
  // else through float, encoded where the file says sRGB.
  const bool asStored = isByteType(image.type) && encoding.bits == 8 && format != "exr";
  const bool srgb = asStored ? image.type == PixelType::Srgb8 : encoding.srgb && format != "exr";
  // Floats into PNG rows are encoded row by row (pngRow), with no float
  // copy of the image.
  const bool encodeRows = format == "png" && image.type == PixelType::F32 && srgb;
  Image converted;
  if (!asStored && !encodeRows && (image.type != PixelType::F32 || srgb)) converted = floatFor(image, srgb);
  const Image& pixels = converted.bytes.empty() ? image : converted;
  // Encoded in memory, then written by us: OpenImageIO's writers do not
  // report a failed write (a full disk gave a truncated file and success).
  // A worker's buffer, reused from file to file (no fresh pages each time).
  thread_local std::vector<unsigned char> encoded;
  if (format == "png") {
    try {
      encodePng(pixels, encoding, srgb, encodeRows, encoded);
    } catch (const Error& e) {
      fail(path, e.what());
    }
  } else if (std::string error = imageCodec().encode(pixels, format, encoding, srgb, encoded); !error.empty()) {
    fail(path, error);
  }
  writeFileAtomically(path, std::as_bytes(std::span(encoded)));
}

void writeDepthImage(const DepthImage& depth, const std::string& path, const ImageEncoding& encoding) {
  if (formatOf(path) != "exr") fail(path, "depth images are exr files");
  ImageEncoding exr = encoding;
  const auto& allowed = codecs("exr");
  if (std::find(allowed.begin(), allowed.end(), exr.codec) == allowed.end()) exr.codec = "";
  thread_local std::vector<unsigned char> encoded;
  if (ownsDepthCodec(exr.codec)) {
    try {
      encodeDepthExr(depth, exr.codec != "none", encoded);
    } catch (const Error& e) {
      fail(path, e.what());
    }
  } else if (std::string error = imageCodec().encodeDepth(depth, exr, encoded); !error.empty()) {
    fail(path, error);
  }
  writeFileAtomically(path, std::as_bytes(std::span(encoded)));
}

DepthImage readDepthImage(const std::string& path) {
  const Image rgba = readImage(path);
  if (rgba.type != PixelType::F32) fail(path, "a depth image must hold floats");
  DepthImage depth(rgba.width, rgba.height);
  const float* v = reinterpret_cast<const float*>(rgba.bytes.data());
  for (size_t i = 0; i < depth.values.size(); ++i) depth.values[i] = v[4 * i];
  return depth;
}

ImageEncoding readImageEncoding(const std::string& path) {
  ImageEncoding e;
  std::string compression;
  bool linear = false;
  if (std::string error = imageCodec().describe(path, e.bits, compression, linear); !error.empty())
    fail(path, error);
  const std::string format = formatOf(path);
  if (format != "png") e.codec = compression;
  // A PNG says (sRGB chunk, or gAMA 1.0 for linear); exr is linear; a tiff
  // carries no tag (the manifest says) and is reported sRGB.
  e.srgb = format != "exr" && !linear;
  return e;
}

std::string readImageAttribute(const std::string& path, const std::string& name) {
  std::string value;
  if (std::string error = imageCodec().attribute(path, name, value); !error.empty()) fail(path, error);
  return value;
}

Image readImage(const std::string& path) {
  Image img;
  if (std::string error = imageCodec().decode(path, img); !error.empty()) fail(path, error);
  return img;
}

}  // namespace mvr
