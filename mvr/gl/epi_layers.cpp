#include "mvr/gl/epi_layers.h"

#include "mvr/error.h"

namespace mvr {

EpiLayersSink::EpiLayersSink(GLuint texture, int width, int views, int scanlines)
    : texture_(texture), width_(width), views_(views), scanlines_(scanlines) {}

unsigned EpiLayersSink::epiTexture(int row, int width, int views, PixelType type) {
  return row == 0 && width == width_ && views == views_ && isByteType(type) ? texture_ : 0;
}

void EpiLayersSink::check(int row, int width, int height, PixelType type) const {
  if (row != 0 || width != width_ || !isByteType(type) || height <= 0)
    fail("EPI layers", "a frame of another row, size or type than the texture's");
}

void EpiLayersSink::putEpi(int row, int scanline, const Image& epi) {
  check(row, epi.width, epi.height == views_ ? 1 : 0, epi.type);
  if (scanline < 0 || scanline >= scanlines_) fail("EPI layers", "a scanline past the texture's layers");
  gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl::TextureSubImage3D(texture_, 0, 0, 0, scanline, width_, views_, 1, GL_RGBA, GL_UNSIGNED_BYTE, epi.bytes.data());
  ++uploads_;
}

// A view's row s is row `view` of layer s: the view's rows, one a layer.
void EpiLayersSink::putView(int row, int view, const Image& image) {
  check(row, image.width, image.height == scanlines_ ? 1 : 0, image.type);
  if (view < 0 || view >= views_) fail("EPI layers", "a view past the texture's rows");
  gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl::TextureSubImage3D(texture_, 0, 0, view, 0, width_, 1, scanlines_, GL_RGBA, GL_UNSIGNED_BYTE,
                        image.bytes.data());
  ++uploads_;
}

}  // namespace mvr
