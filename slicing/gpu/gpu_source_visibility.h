#pragma once
// Conservative visibility (slicing/source_visibility.h, hideInvisible) as
// compute passes over source layers in GPU memory (DeviceLayers): each
// pixel of a layer behind its source's nearest is dropped, its depth set
// to 0 in the store, where the nearest layer hides it from every view of
// the track. The same decisions as hideInvisible, the same arithmetic
// (double where it is double), so interp's GPU path keeps the layers its
// host path keeps.
#include <vector>

#include "mvr/baselines/source_layers.h"
#include "mvr/camera.h"
#include "mvr/gl/gl_handles.h"

namespace mvr {

// One layer's pixels before the test and those it kept (a nearest layer
// is not tested: both 0).
struct LayerVisibility {
  long covered = 0, kept = 0;
};

class GpuVisibility {
 public:
  GpuVisibility();  // needs a current GL context

  // Tests every layer of the store behind its source's nearest (a
  // source's layers together, nearest first, as the store is filled) for
  // cam's track, with the slices' overlap; one readback, of the counts.
  std::vector<LayerVisibility> hide(DeviceLayers& layers, const ShearingCamera& cam, float overlap);

 private:
  gl::Program rows_, hide_;
  gl::Buffer prefix_;  // scratch: per front layer row, its prefix counts
  size_t prefixSize_ = 0;
};

}  // namespace mvr
