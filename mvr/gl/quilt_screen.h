#pragma once
// What mvr live shows (issue 48): the views as a texture, uploaded once a
// frame (a quilt, an EPI volume or a view array: mvr/lenticular.h), drawn through a
// lenticular display's mapping (mvr/gl/lenticular_pass.h) at the panel's
// size, or, without a calibration, as the quilt scaled to the screen.
// Into the window's framebuffer, or offscreen where there is no window
// (headless EGL); read() gives what was drawn.
#include <memory>
#include <optional>

#include "mvr/gl/gl_handles.h"
#include "mvr/gl/lenticular_pass.h"
#include "mvr/image.h"

namespace mvr {

class QuiltScreen {
 public:
  // A screen of width x height showing the views of `grid` (8-bit RGBA,
  // in `layout`) through `panel` (its size the screen's), or as the quilt
  // scaled. offscreen: draws into a framebuffer of its own instead of the
  // window's.
  QuiltScreen(int width, int height, const QuiltGrid& grid, ViewLayout layout, std::optional<LenticularMap> panel,
              bool offscreen);
  int width() const { return width_; }
  int height() const { return height_; }
  void upload(const Image& quilt);
  // The texture upload() fills: a renderer in this context may write it
  // instead (the layered layouts: mvr/gl/view_layers.h).
  GLuint viewsTexture() const { return quilt_.id(); }
  ViewLayout layout() const { return layout_; }
  void draw() const;
  void finish() const;  // waits for the GL to finish drawing
  Image read() const;   // the screen as drawn, rows top first

 private:
  glm::ivec3 layerBox() const;  // a layered texture's width, height and layers
  int width_, height_;
  QuiltGrid grid_;
  ViewLayout layout_;
  int uploadWidth_, uploadHeight_;  // the image upload() takes
  gl::Texture quilt_;
  std::unique_ptr<LenticularPass> panel_;
  gl::Program scaled_;
  gl::VertexArray vao_;
  gl::Texture target_;  // offscreen only
  gl::Framebuffer fbo_;
};

}  // namespace mvr
