#pragma once
// The panel mapping (mvr/lenticular.h) as one GL pass: a quilt
// texture in, the panel's native image out, into the bound framebuffer
// (a window's, shown as it is drawn) or read back.
#include "mvr/lenticular.h"
#include "mvr/gl/gl_handles.h"
#include "mvr/image.h"

namespace mvr {

class LenticularPass {
 public:
  // Needs a current GL 4.5 context.
  explicit LenticularPass(const LenticularMap& map, ViewLayout layout = ViewLayout::Quilt);
  const LenticularMap& map() const { return map_; }
  // The views, 8-bit RGBA with rows top first as Image holds them: a quilt
  // (a 2D texture, row 0 the quilt's top row), an EPI volume (a 2D array
  // texture, layer s scanline s's EPI) or a view array (layer v view v),
  // into the bound draw framebuffer at (0, 0), screenW x screenH.
  void draw(GLuint viewsTexture) const;
  // The views (a quilt, epiVolumeOf's layout, or the views one under
  // another) to the native image, offscreen: the GPU twin of nativeImage().
  Image render(const Image& views) const;

 private:
  LenticularMap map_;
  ViewLayout layout_;
  gl::Program program_;
  gl::VertexArray vao_;
};

}  // namespace mvr
