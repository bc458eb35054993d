#pragma once
// What mvr view shows in its window: one view at 1:1 on top and, below
// it, an EPI (one row a view) scaled to the panel's rows, each with an
// optional marker row, over black and opaque. The GL side of the viewer:
// textures, the pass that draws them into the default framebuffer, and
// reading the window back.
#include <glm/glm.hpp>

#include "mvr/gl/gl_handles.h"
#include "mvr/image.h"

namespace mvr::gl {

class ViewPanel {
 public:
  // Views of width x height, EPIs of `views` rows shown in `panelRows`
  // window rows. Needs a current context with a default framebuffer.
  ViewPanel(int width, int height, int views, int panelRows);
  int windowRows() const { return height_ + panelRows_; }
  // 8-bit images as stored (display values): the view, and the EPI.
  void upload(const Image& view, const Image& epi);
  // marker: x the EPI row (view), y the view's row (scanline); -1: none.
  void draw(glm::ivec2 marker);
  // The window as drawn, rows top first.
  Image read() const;

 private:
  int width_, height_, views_, panelRows_;
  Program program_;
  Texture view_, epi_;
  VertexArray vao_;
};

}  // namespace mvr::gl
