// The module mvr_oiio: OpenImageIO behind the ImageCodec table
// (mvr/images/image_codec.h). Only this file includes OpenImageIO.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <OpenImageIO/strutil.h>

#include <cstring>

#include "mvr/images/image_codec.h"

namespace mvr {
namespace {

constexpr int kPngFilterNone = 0x08, kPngAllFilters = 0xF8;  // libpng's PNG_FILTER_* bits

bool saysLinear(const OIIO::ImageSpec& spec) {
  return OIIO::Strutil::iequals(spec.get_string_attribute("oiio:ColorSpace"), "linear");
}

std::string encode(const Image& pixels, const std::string& format, const ImageEncoding& encoding,
                   bool srgbTag, std::vector<unsigned char>& out) {
  auto output = OIIO::ImageOutput::create(format);
  if (!output) return "no image writer for " + format;
  const OIIO::TypeDesc fileType = format == "exr" ? (encoding.bits == 16 ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT)
                                  : encoding.bits == 16 ? OIIO::TypeDesc::UINT16
                                                        : OIIO::TypeDesc::UINT8;
  OIIO::ImageSpec spec(pixels.width, pixels.height, 4, fileType);
  if (format == "png") {
    // sRGB, gAMA and cHRM chunks, or gAMA 1.0. TIFF has no standard tag
    // (and OpenImageIO 2.4's sRGB EXIF tag left TIFFs unreadable): the
    // manifest's color_encoding says.
    spec.attribute("oiio:ColorSpace", srgbTag ? "sRGB" : "linear");
    spec.attribute("png:compressionLevel", encoding.pngLevel);
    // Row filters: none at the fast levels, libpng's adaptive choice from 4
    // on. Measured at level 1 on rendered 640x480 views (docs/BENCHMARKS.md):
    // no filter encodes 2-3x faster for files 2% smaller to 14% larger.
    spec.attribute("png:filter", encoding.pngLevel <= 3 ? kPngFilterNone : kPngAllFilters);
  } else {
    spec.attribute("compression", encoding.codec.empty() ? defaultCodec(format) : encoding.codec);
  }
  for (const auto& [name, value] : encoding.attributes) spec.attribute(name, value);
  // Our images hold straight alpha (docs/CONVENTIONS.md). Unless told so,
  // OpenImageIO takes them as premultiplied: it divided a PNG's colour by
  // its alpha once more, and tags a TIFF's alpha as associated.
  spec.attribute("oiio:UnassociatedAlpha", 1);
  const OIIO::TypeDesc memType = isByteType(pixels.type) ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::FLOAT;
  out.clear();
  OIIO::Filesystem::IOVecOutput proxy(out);
  const std::string name = "image." + format;
  if (!output->supports("ioproxy") || !output->set_ioproxy(&proxy)) return "image writer cannot encode to memory";
  if (!output->open(name, spec) || !output->write_image(memType, pixels.bytes.data()) || !output->close())
    return "cannot encode image: " + output->geterror();
  return "";
}

std::string encodeDepth(const DepthImage& depth, const ImageEncoding& encoding, std::vector<unsigned char>& out) {
  auto output = OIIO::ImageOutput::create("exr");
  if (!output) return "no image writer for exr";
  OIIO::ImageSpec spec(depth.width, depth.height, 1, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"Z"};
  spec.z_channel = 0;
  spec.attribute("compression", encoding.codec.empty() ? defaultCodec("exr") : encoding.codec);
  out.clear();
  OIIO::Filesystem::IOVecOutput proxy(out);
  if (!output->supports("ioproxy") || !output->set_ioproxy(&proxy)) return "image writer cannot encode to memory";
  if (!output->open("depth.exr", spec) || !output->write_image(OIIO::TypeDesc::FLOAT, depth.values.data()) ||
      !output->close())
    return "cannot encode depth image: " + output->geterror();
  return "";
}

std::string decode(const std::string& path, Image& img) {
  // Pixels as the file stores them: OpenImageIO premultiplies a PNG's
  // colour by its alpha on reading unless told not to, and PNG, like our
  // images, holds straight alpha.
  OIIO::ImageSpec config;
  config.attribute("oiio:UnassociatedAlpha", 1);
  auto in = OIIO::ImageInput::open(path, &config);
  if (!in) return "cannot read image: " + OIIO::geterror();
  const OIIO::ImageSpec& spec = in->spec();
  const bool isFloat = spec.format.basetype == OIIO::TypeDesc::FLOAT ||
                       spec.format.basetype == OIIO::TypeDesc::HALF;
  // 8-bit files are sRGB unless they say linear (a PNG's gAMA 1.0).
  img = Image(spec.width, spec.height, isFloat ? PixelType::F32 : saysLinear(spec) ? PixelType::U8 : PixelType::Srgb8);
  // Read the file's channels, then widen to RGBA (alpha 1 when absent).
  const int nc = spec.nchannels;
  const size_t cb = Image::channelBytes(img.type);
  std::vector<uint8_t> raw(size_t(spec.width) * spec.height * nc * cb);
  if (!in->read_image(0, 0, 0, nc, isFloat ? OIIO::TypeDesc::FLOAT : OIIO::TypeDesc::UINT8, raw.data()))
    return "cannot read image: " + in->geterror();
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
  return "";
}

std::string describe(const std::string& path, int& bits, std::string& compression, bool& linear) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return "cannot read image: " + OIIO::geterror();
  const OIIO::ImageSpec& spec = in->spec();
  bits = int(spec.format.size()) * 8;
  compression = spec.get_string_attribute("compression");
  linear = saysLinear(spec);
  return "";
}

std::string attribute(const std::string& path, const std::string& name, std::string& value) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) return "cannot read image: " + OIIO::geterror();
  value = in->spec().get_string_attribute(name);
  return "";
}

const ImageCodec kCodec{encode, encodeDepth, decode, describe, attribute};

}  // namespace
}  // namespace mvr

extern "C" __attribute__((visibility("default"))) const mvr::ImageCodec* mvrImageCodec() { return &mvr::kCodec; }
