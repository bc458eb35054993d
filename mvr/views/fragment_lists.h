#pragma once
// Every fragment of one pass of the geometry, kept per pixel as a linked
// list in GPU memory (an A-buffer), so that all of a view's depth-peeled
// layers come from a single pass of the mesh. Peeling draws the mesh once
// a layer, and on llvmpipe a pass of the scanned bunny's 70K triangles
// costs about 16 ms at 160x120 however few pixels it keeps.
#include <cstddef>
#include <cstdint>

#include "mvr/gl/gl_handles.h"

namespace mvr {

class FragmentLists {
 public:
  // GLSL for the passes that fill and read the lists: their buffers
  // (shader storage binding points 2-6), kListEnd, listHead(pixel) and,
  // where COLLECT is defined, append(albedo, normal) for the fragment
  // being shaded.
  static const char* glsl();

  // Before a pass that fills the lists for a width x height view: the
  // lists emptied, the buffers bound, and an attachment-less framebuffer
  // of that size bound with its viewport (nothing is drawn but the lists).
  void beginCollect(int width, int height);
  // After that pass: Fits when every fragment found room; Grown when the
  // storage grew to hold them (draw the pass again); TooLarge when they
  // would need more than the limit (setMaxBytes) or the GL's largest
  // buffer.
  enum class Fit { Fits, Grown, TooLarge };
  Fit check();
  // Binds the buffers for a pass that reads the lists.
  void bindForReading() const;

  // Per fragment: albedo and depth, normal and material, primitive and
  // next: 40 bytes.
  static constexpr size_t kBytesPerFragment = 40;
  static constexpr size_t kMaxBytes = size_t(1) << 30;
  // The lists' memory limit (default kMaxBytes); tests lower it to reach
  // the fallback.
  static void setMaxBytes(size_t bytes);

 private:
  void allocate(size_t fragments);

  int width_ = 0, height_ = 0;
  size_t capacity_ = 0, pixels_ = 0;  // fragments and pixels allocated
  gl::Buffer header_, heads_, surface_, normal_, link_;
  gl::Framebuffer fbo_;
};

}  // namespace mvr
