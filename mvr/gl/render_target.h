#pragma once
// An offscreen colour + depth target (optionally layered) and the GL state
// every renderer shares: reversed zero-to-one depth in a float buffer.
#include "mvr/gl/gl_handles.h"
#include "mvr/image.h"

namespace mvr {

class RenderTarget {
 public:
  // layers = 0: plain 2D; otherwise a 2D array of that many layers.
  // storage: the colour buffer's own format when it differs from the
  // images read back (F32 to accumulate passes, read as U8 with clamping,
  // or as Srgb8 through an encoding blit). An Srgb8 target is GL sRGB:
  // shaders write linear values, GL encodes them (and blends in linear).
  RenderTarget(int width, int height, PixelType type, int layers = 0);
  RenderTarget(int width, int height, PixelType type, int layers, PixelType storage);

  int width() const { return width_; }
  int height() const { return height_; }
  PixelType type() const { return type_; }
  GLuint framebuffer() const { return fbo_.id(); }
  GLuint colorTexture() const { return color_.id(); }

  void bind() const;           // binds, sets the viewport, sRGB encoding on
  void clear() const;          // colour 0, depth 0 (far in reversed Z)
  Image read() const;          // 2D target: whole image, rows top first
  // Rows [y, y + h) into an existing image of the target's width.
  void readRows(int y, int h, Image& out, int outY) const;
  // The framebuffer whose rows [y, y + h) hold the pixels as read back:
  // this one, or (F32 storage read as Srgb8) a copy the rows were just
  // encoded into.
  GLuint readableFramebuffer(int y, int h) const;
  // Whether the pixels as read back are 8-bit texels of a 2D target, which
  // a copy on the GPU can take (not F32 storage read as U8).
  bool copiesBytes() const { return !layers_ && (isByteType(storage_) || resolved_); }
  // The pixels as read back into layer `layer` of an RGBA8 2D array
  // texture of the target's width, on the GPU; needs copiesBytes(): rows
  // [y, y + h) to rows [toY, toY + h) of the layer, or the whole target.
  void copyRows(int y, int h, GLuint texture, int toY, int layer) const;
  void copyToLayer(GLuint texture, int layer) const { copyRows(0, height_, texture, 0, layer); }

 private:
  int width_, height_, layers_;
  PixelType type_, storage_;
  gl::Texture color_, depth_;
  gl::Framebuffer fbo_;
  gl::Texture resolved_;  // only when F32 storage is read as Srgb8
  gl::Framebuffer resolveFbo_;
};

// The GL type of a PixelType's channels, for reads and uploads.
inline GLenum glChannelType(PixelType t) { return isByteType(t) ? GL_UNSIGNED_BYTE : GL_FLOAT; }

// Reads rows of the bound read framebuffer as they are stored (into a
// bound pixel-pack buffer when dst is an offset): an sRGB target gives its
// encoded bytes. FRAMEBUFFER_SRGB is off during the read, as drivers
// differ on whether a read with it on decodes.
void readStoredPixels(int y, int width, int h, PixelType type, void* dst);

// A framebuffer's 8-bit pixels (0, 0, width, height) as they are stored,
// rows top first (GL's run up): what a window or a pass drew.
Image readFramebuffer(GLuint framebuffer, int width, int height);

// Reversed Z: depth test GREATER, clear to 0, zero-to-one clip depth.
void setDepthConvention();

}  // namespace mvr
