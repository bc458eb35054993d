#pragma once
// A frame sink whose views land in a GL 2D array texture, on the GPU, in
// one of the layered layouts (mvr/lenticular.h): an EPI volume (layer s
// scanline s's EPI, its row v view v's) or a view array (layer v view v,
// rows top first). mvr live's screen samples that texture. A renderer
// that writes the layers itself reads nothing back: the GPU spans store
// their EPIs into an EPI volume's (FrameSink::epiTexture), the view loop
// copies each view it draws into a view array's (FrameSink::viewTexture).
// Others hand on EPIs or views, uploaded as they come.
#include "mvr/gl/gl_api.h"
#include "mvr/lenticular.h"
#include "mvr/renderer.h"

namespace mvr {

class ViewLayersSink final : public FrameSink {
 public:
  // `texture`: RGBA8 in the current context, not owned: width x views x
  // scanlines for an EPI volume, width x scanlines x views for a view
  // array. One row of views.
  ViewLayersSink(GLuint texture, ViewLayout layout, int width, int views, int scanlines);
  unsigned epiTexture(int row, int width, int views, PixelType type) override;
  unsigned viewTexture(int row, int width, int height, int views, PixelType type) override;
  void putEpi(int row, int scanline, const Image& epi) override;
  void putView(int row, int view, const Image& image) override;
  // EPIs and views uploaded so far: none where the renderer wrote the
  // layers itself.
  int uploads() const { return uploads_; }

 private:
  // The box of texels (x, y, layer) the image fills, w x h x depth: an
  // image's rows one after another in it.
  void upload(const Image& image, int y, int layer, int h, int depth);
  GLuint texture_;
  ViewLayout layout_;
  int width_, views_, scanlines_;
  int uploads_ = 0;
};

}  // namespace mvr
