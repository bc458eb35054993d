#include "mvr/gl/render_target.h"

#include "mvr/error.h"

namespace mvr {
namespace {

GLenum colorFormat(PixelType t) { return t == PixelType::U8 ? GL_RGBA8 : GL_RGBA32F; }

}  // namespace

RenderTarget::RenderTarget(int width, int height, PixelType type, int layers)
    : RenderTarget(width, height, type, layers, type) {}

RenderTarget::RenderTarget(int width, int height, PixelType type, int layers, PixelType storage)
    : width_(width), height_(height), layers_(layers), type_(type),
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
  if (gl::CheckNamedFramebufferStatus(fbo_.id(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    fail("GL", "render target " + std::to_string(width) + "x" + std::to_string(height) +
                   " is incomplete");
}

void RenderTarget::bind() const {
  gl::BindFramebuffer(GL_FRAMEBUFFER, fbo_.id());
  gl::Viewport(0, 0, width_, height_);
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
  gl::BindFramebuffer(GL_READ_FRAMEBUFFER, fbo_.id());
  gl::PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl::ReadPixels(0, y, width_, h, GL_RGBA, glChannelType(type_), out.row(outY));
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
