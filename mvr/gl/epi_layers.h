#pragma once
// A frame sink whose EPIs land in a GL 2D array texture, on the GPU: layer
// s scanline s's EPI, its row v view v's (RGBA8, the EPI volume's layout:
// mvr/lenticular.h). mvr live's screen samples that texture; a renderer
// that writes the layers itself (FrameSink::epiTexture: the GPU spans)
// reads nothing back. Others hand on EPIs or views, uploaded as they come.
#include "mvr/gl/gl_api.h"
#include "mvr/renderer.h"

namespace mvr {

class EpiLayersSink final : public FrameSink {
 public:
  // `texture`: width x views x scanlines, RGBA8, in the current context;
  // not owned. One row of views.
  EpiLayersSink(GLuint texture, int width, int views, int scanlines);
  unsigned epiTexture(int row, int width, int views, PixelType type) override;
  void putEpi(int row, int scanline, const Image& epi) override;
  void putView(int row, int view, const Image& image) override;
  // EPIs and views uploaded so far: none where the renderer wrote the
  // layers itself.
  int uploads() const { return uploads_; }

 private:
  void check(int row, int width, int height, PixelType type) const;
  GLuint texture_;
  int width_, views_, scanlines_;
  int uploads_ = 0;
};

}  // namespace mvr
