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
  explicit LenticularPass(const LenticularMap& map);
  const LenticularMap& map() const { return map_; }
  // The quilt, 8-bit RGBA with rows top first as Image holds them (a
  // texture of that layout: row 0 the quilt's top row), into the bound
  // draw framebuffer at (0, 0), screenW x screenH.
  void draw(GLuint quiltTexture) const;
  // An 8-bit quilt to the native image, offscreen: the GPU twin of
  // nativeImage().
  Image render(const Image& quilt) const;

 private:
  LenticularMap map_;
  gl::Program program_;
  gl::VertexArray vao_;
};

}  // namespace mvr
