#include "mvr/gl/render_target.h"

#include <cstring>
#include <vector>

#include "mvr/error.h"

namespace mvr {
namespace {

GLenum colorFormat(PixelType t) {
  switch (t) {
    case PixelType::U8: return GL_RGBA8;
    case PixelType::Srgb8: return GL_SRGB8_ALPHA8;
    case PixelType::F32: break;
  }
  return GL_RGBA32F;
}

void checkComplete(GLuint fbo, int width, int height) {
  if (gl::CheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    fail("GL", "render target " + std::to_string(width) + "x" + std::to_string(height) +
                   " is incomplete");
}

}  // namespace

RenderTarget::RenderTarget(int width, int height, PixelType type, int layers)
    : RenderTarget(width, height, type, layers, type) {}

RenderTarget::RenderTarget(int width, int height, PixelType type, int layers, PixelType storage)
    : width_(width), height_(height), layers_(layers), type_(type), storage_(storage),
      color_(layers ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D),
      depth_(layers ? GL_TEXTURE_2D_ARRAY : GL_TEXTURE_2D),
      fbo_(gl::Framebuffer::create()) {
  if (layers) {
    gl::TextureStorage3D(color_.id(), 1, colorFormat(storage), width, height, layers);
    gl::TextureStorage3D(depth_.id(), 1, GL_DEPTH_COMPONENT32F, width, height, layers);
  } else {
    gl::TextureStorage2D(color_.id(), 1, colorFormat(storage), width, height);
    gl::TextureStorage2D(depth_.id(), 1, GL_DEPTH_COMPONENT32F, width, height);
  }
  gl::checkError("allocating render target");
  gl::NamedFramebufferTexture(fbo_.id(), GL_COLOR_ATTACHMENT0, color_.id(), 0);
  gl::NamedFramebufferTexture(fbo_.id(), GL_DEPTH_ATTACHMENT, depth_.id(), 0);
  checkComplete(fbo_.id(), width, height);
  if (type == PixelType::Srgb8 && storage != type) {
    if (layers) fail("GL", "a layered target cannot be read in another format");
    resolved_ = gl::Texture(GL_TEXTURE_2D);
    gl::TextureStorage2D(resolved_.id(), 1, colorFormat(type), width, height);
    resolveFbo_ = gl::Framebuffer::create();
    gl::NamedFramebufferTexture(resolveFbo_.id(), GL_COLOR_ATTACHMENT0, resolved_.id(), 0);
    checkComplete(resolveFbo_.id(), width, height);
  }
}

void RenderTarget::bind() const {
  gl::BindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
  gl::Viewport(0, 0, width_, height_);
  gl::Enable(GL_FRAMEBUFFER_SRGB);  // no effect on linear targets
}

GLuint RenderTarget::readableFramebuffer(int y, int h) const {
  if (!resolveFbo_.id()) return fbo_.id();
  // The blit converts float to sRGB bytes (encoding on with FRAMEBUFFER_SRGB).
  gl::Enable(GL_FRAMEBUFFER_SRGB);
  gl::BlitNamedFramebuffer(fbo_.id(), resolveFbo_.id(), 0, y, width_, y + h, 0, y, width_, y + h,
                           GL_COLOR_BUFFER_BIT, GL_NEAREST);
  return resolveFbo_.id();
}

void RenderTarget::copyRows(int y, int h, GLuint texture, int toY, int layer) const {
  if (!copiesBytes()) fail("GL", "the render target's pixels are not stored as bytes");
  // A raw copy of the stored bytes (sRGB and RGBA8 texels are alike to
  // it), from the encoded copy where F32 storage is read as Srgb8.
  readableFramebuffer(y, h);
  const GLuint source = resolved_ ? resolved_.id() : color_.id();
  gl::CopyImageSubData(source, GL_TEXTURE_2D, 0, 0, y, 0, texture, GL_TEXTURE_2D_ARRAY, 0, 0, toY, layer, width_, h,
                       1);
}

void RenderTarget::clear() const {
  // Clears obey the write masks; a pass that tests depth EQUAL leaves the
  // depth mask off, and a stale depth buffer would hide the next batch.
  gl::DepthMask(GL_TRUE);
  gl::ColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  const float zero[4] = {0, 0, 0, 0};
  gl::ClearNamedFramebufferfv(fbo_.id(), GL_COLOR, 0, zero);
  gl::ClearNamedFramebufferfi(fbo_.id(), GL_DEPTH_STENCIL, 0, 0.0f, 0);
}

Image RenderTarget::read() const {
  Image img(width_, height_, type_);
  readRows(0, height_, img, 0);
  return img;
}

void RenderTarget::readRows(int y, int h, Image& out, int outY) const {
  gl::BindFramebuffer(GL_READ_FRAMEBUFFER, readableFramebuffer(y, h));
  readStoredPixels(y, width_, h, type_, out.row(outY));
}

void readStoredPixels(int y, int width, int h, PixelType type, void* dst) {
  gl::PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl::Disable(GL_FRAMEBUFFER_SRGB);
  gl::ReadPixels(0, y, width, h, GL_RGBA, glChannelType(type), dst);
  gl::Enable(GL_FRAMEBUFFER_SRGB);
}

Image readFramebuffer(GLuint framebuffer, int width, int height) {
  Image out(width, height, PixelType::Srgb8);
  std::vector<uint8_t> raw(out.bytes.size());
  gl::BindFramebuffer(GL_READ_FRAMEBUFFER, framebuffer);
  gl::PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl::ReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, raw.data());
  for (int y = 0; y < height; ++y)
    std::memcpy(out.row(y), raw.data() + size_t(height - 1 - y) * out.rowBytes(), out.rowBytes());
  return out;
}

void setDepthConvention() {
  gl::ClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  gl::Enable(GL_DEPTH_TEST);
  gl::DepthFunc(GL_GREATER);
  gl::DepthMask(GL_TRUE);
  gl::Disable(GL_CULL_FACE);
  gl::Disable(GL_BLEND);
}

}  // namespace mvr
