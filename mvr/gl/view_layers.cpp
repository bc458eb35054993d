#include "mvr/gl/view_layers.h"

#include "mvr/error.h"

namespace mvr {

ViewLayersSink::ViewLayersSink(GLuint texture, ViewLayout layout, int width, int views, int scanlines)
    : texture_(texture), layout_(layout), width_(width), views_(views), scanlines_(scanlines) {
  if (layout == ViewLayout::Quilt) fail("view layers", "a quilt is not a layered layout");
}

unsigned ViewLayersSink::epiTexture(int row, int width, int views, PixelType type) {
  const bool mine = layout_ == ViewLayout::EpiVolume && row == 0 && width == width_ && views == views_;
  return mine && isByteType(type) ? texture_ : 0;
}

unsigned ViewLayersSink::viewTexture(int row, int width, int height, int views, PixelType type) {
  const bool mine = layout_ == ViewLayout::ViewArray && row == 0 && width == width_ && height == scanlines_ &&
                    views == views_;
  return mine && isByteType(type) ? texture_ : 0;
}

void ViewLayersSink::upload(const Image& image, int y, int layer, int h, int depth) {
  gl::PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl::TextureSubImage3D(texture_, 0, 0, y, layer, width_, h, depth, GL_RGBA, GL_UNSIGNED_BYTE, image.bytes.data());
  ++uploads_;
}

// An EPI's row v is row s of view v.
void ViewLayersSink::putEpi(int row, int scanline, const Image& epi) {
  if (row != 0 || epi.width != width_ || epi.height != views_ || !isByteType(epi.type))
    fail("view layers", "an EPI of another row, size or type than the texture's");
  if (scanline < 0 || scanline >= scanlines_) fail("view layers", "a scanline past the texture's");
  if (layout_ == ViewLayout::EpiVolume)
    upload(epi, 0, scanline, views_, 1);
  else
    upload(epi, scanline, 0, 1, views_);
}

// A view's row s is row v of EPI s.
void ViewLayersSink::putView(int row, int view, const Image& image) {
  if (row != 0 || image.width != width_ || image.height != scanlines_ || !isByteType(image.type))
    fail("view layers", "a view of another row, size or type than the texture's");
  if (view < 0 || view >= views_) fail("view layers", "a view past the texture's");
  if (layout_ == ViewLayout::EpiVolume)
    upload(image, view, 0, 1, scanlines_);
  else
    upload(image, 0, view, scanlines_, 1);
}

}  // namespace mvr
