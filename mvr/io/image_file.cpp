#include "mvr/io/image_file.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <vector>

#include "mvr/color.h"
#include "mvr/error.h"
#include "mvr/io/atomic_file.h"

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

std::string defaultCodec(const std::string& format) { return format == "png" ? "" : "zip"; }

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

constexpr int kPngFilterNone = 0x08, kPngAllFilters = 0xF8;  // libpng's PNG_FILTER_* bits

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

}  // namespace

void writeImage(const Image& image, const std::string& path, const ImageEncoding& encoding) {
  const std::string format = formatOf(path);
  auto out = OIIO::ImageOutput::create(path);
  if (!out) fail(path, "no image writer for this extension");
  checkEncoding(format, encoding);
  const OIIO::TypeDesc fileType = format == "exr" ? (encoding.bits == 16 ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT)
                                  : encoding.bits == 16 ? OIIO::TypeDesc::UINT16
                                                        : OIIO::TypeDesc::UINT8;
  // Byte images go out as stored when the file holds bytes; everything
  // else through float, encoded where the file says sRGB.
  const bool asStored = isByteType(image.type) && encoding.bits == 8 && format != "exr";
  const bool srgb = asStored ? image.type == PixelType::Srgb8 : encoding.srgb && format != "exr";
  Image converted;
  if (!asStored && (image.type != PixelType::F32 || srgb)) converted = floatFor(image, srgb);
  const Image& pixels = converted.bytes.empty() ? image : converted;
  OIIO::ImageSpec spec(image.width, image.height, 4, fileType);
  if (format == "png") {
    // sRGB, gAMA and cHRM chunks, or gAMA 1.0. TIFF has no standard tag
    // (and OpenImageIO 2.4's sRGB EXIF tag left TIFFs unreadable): the
    // manifest's color_encoding says.
    spec.attribute("oiio:ColorSpace", srgb ? "sRGB" : "linear");
    spec.attribute("png:compressionLevel", encoding.pngLevel);
    // Row filters: none at the fast levels, libpng's adaptive choice from 4
    // on. Measured at level 1 on rendered 640x480 views (docs/BENCHMARKS.md):
    // no filter encodes 2-3x faster for files 2% smaller to 14% larger.
    spec.attribute("png:filter", encoding.pngLevel <= 3 ? kPngFilterNone : kPngAllFilters);
  } else {
    spec.attribute("compression", encoding.codec.empty() ? defaultCodec(format) : encoding.codec);
  }
  const OIIO::TypeDesc memType = isByteType(pixels.type) ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
  // Encoded in memory, then written by us: OpenImageIO's writers do not
  // report a failed write (a full disk gave a truncated file and success).
  // A worker's buffer, reused from file to file (no fresh pages each time).
  thread_local std::vector<unsigned char> encoded;
  encoded.clear();
  OIIO::Filesystem::IOVecOutput proxy(encoded);
  if (!out->supports("ioproxy") || !out->set_ioproxy(&proxy)) fail(path, "image writer cannot encode to memory");
  if (!out->open(path, spec) || !out->write_image(memType, pixels.bytes.data()) || !out->close())
    fail(path, "cannot encode image: " + out->geterror());
  writeFileAtomically(path, std::as_bytes(std::span(encoded)));
}

ImageEncoding readImageEncoding(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) fail(path, "cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  ImageEncoding e;
  e.bits = int(spec.format.size()) * 8;
  if (formatOf(path) != "png") e.codec = spec.get_string_attribute("compression");
  // A PNG says (sRGB chunk, or gAMA 1.0 for linear); others: exr linear,
  // tiff unknown here (the manifest says), reported as sRGB.
  const std::string space = spec.get_string_attribute("oiio:ColorSpace");
  e.srgb = formatOf(path) != "exr" && !OIIO::Strutil::iequals(space, "linear");
  return e;
}

Image readImage(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) fail(path, "cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  const bool isFloat = spec.format.basetype == OIIO::TypeDesc::FLOAT ||
                       spec.format.basetype == OIIO::TypeDesc::HALF;
  // 8-bit files are sRGB unless they say linear (a PNG's gAMA 1.0).
  const bool linear = OIIO::Strutil::iequals(spec.get_string_attribute("oiio:ColorSpace"), "linear");
  Image img(spec.width, spec.height,
            isFloat ? PixelType::F32 : linear ? PixelType::U8 : PixelType::Srgb8);
  // Read the file's channels, then widen to RGBA (alpha 1 when absent).
  const int nc = spec.nchannels;
  const size_t cb = Image::channelBytes(img.type);
  std::vector<uint8_t> raw(size_t(spec.width) * spec.height * nc * cb);
  if (!in->read_image(0, 0, 0, nc, isFloat ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8,
                      raw.data()))
    fail(path, "cannot read image: " + in->geterror());
  const size_t n = size_t(spec.width) * spec.height;
  for (size_t i = 0; i < n; ++i) {
    for (int c = 0; c < 4; ++c) {
      int src = c < nc ? c : (c == 3 ? -1 : nc - 1);  // grey fills rgb, opaque alpha
      uint8_t* dst = img.bytes.data() + (i * 4 + c) * cb;
      if (src >= 0) {
        std::memcpy(dst, raw.data() + (i * nc + src) * cb, cb);
      } else if (isFloat) {
        float one = 1.0f;
        std::memcpy(dst, &one, 4);
      } else {
        *dst = 255;
      }
    }
  }
  return img;
}

}  // namespace mvr
