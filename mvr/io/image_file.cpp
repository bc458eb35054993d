#include "mvr/io/image_file.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cstring>
#include <filesystem>

#include "mvr/error.h"
#include "mvr/io/atomic_file.h"

namespace mvr {

void writeImage(const Image& image, const std::string& path, int bits, int pngCompression) {
  namespace fs = std::filesystem;
  const std::string ext = fs::path(path).extension().string();
  auto out = OIIO::ImageOutput::create(path);
  if (!out) fail(path, "no image writer for this extension");
  const bool wantsFloat = ext == ".exr";
  OIIO::TypeDesc fileType = wantsFloat   ? OIIO::TypeDesc::FLOAT
                            : bits == 16 ? OIIO::TypeDesc::UINT16
                                         : OIIO::TypeDesc::UINT8;
  OIIO::ImageSpec spec(image.width, image.height, 4, fileType);
  if (ext == ".png") spec.attribute("png:compressionLevel", std::clamp(pngCompression, 0, 9));
  const OIIO::TypeDesc memType = image.type == PixelType::U8 ? OIIO::TypeDesc::UINT8
                                                             : OIIO::TypeDesc::FLOAT;
  // Encoded in memory, then written by us: OpenImageIO's writers do not
  // report a failed write (a full disk gave a truncated file and success).
  std::vector<unsigned char> encoded;
  OIIO::Filesystem::IOVecOutput proxy(encoded);
  if (!out->supports("ioproxy") || !out->set_ioproxy(&proxy)) fail(path, "image writer cannot encode to memory");
  if (!out->open(path, spec) || !out->write_image(memType, image.bytes.data()) || !out->close())
    fail(path, "cannot encode image: " + out->geterror());
  writeFileAtomically(path, std::as_bytes(std::span(encoded)));
}

Image readImage(const std::string& path) {
  auto in = OIIO::ImageInput::open(path);
  if (!in) fail(path, "cannot read image: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  const bool isFloat = spec.format.basetype == OIIO::TypeDesc::FLOAT ||
                       spec.format.basetype == OIIO::TypeDesc::HALF;
  Image img(spec.width, spec.height, isFloat ? PixelType::F32 : PixelType::U8);
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
