#pragma once
// The image-based back end's two uses of parallax (slicing/
// source_visibility.h) as compute passes over source layers in GPU memory
// (DeviceLayers), with their host functions' arithmetic (double where it
// is double), so that interp's GPU path keeps the layers and adds the
// sources its host path does:
//  - conservative visibility (hideInvisible): each pixel of a layer behind
//    its source's nearest is dropped, its depth set to 0 in the store,
//    where the nearest layer hides it from every view of the track;
//  - hole counting (countHoles) for hierarchical acquisition.
#include <cstdint>
#include <vector>

#include "mvr/camera.h"
#include "mvr/gl/gl_handles.h"
#include "mvr/views/source_layers.h"

namespace mvr {

// One layer's pixels before the test and those it kept (a nearest layer
// is not tested: both 0).
struct LayerVisibility {
  long covered = 0, kept = 0;
};

class GpuVisibility {
 public:
  GpuVisibility();  // needs a current GL context

  // Tests every layer of the store from `from` on that lies behind its
  // source's nearest (a source's layers together, nearest first, as the
  // store is filled) for cam's track, with the slices' overlap; one
  // readback, of the counts (per layer of the store; 0 before `from`).
  std::vector<LayerVisibility> hide(DeviceLayers& layers, const ShearingCamera& cam, float overlap, int from = 0);

  // countHoles over the store's layers whose flag in `use` is set (a
  // source's layers together, nearest first): the holes they leave in the
  // view at camera x eyeX. One readback.
  long holes(const DeviceLayers& layers, const std::vector<uint8_t>& use, const ShearingCamera& cam, double eyeX,
             float overlap);

 private:
  gl::Program rows_, hide_, range_, splat_, gaps_;
  gl::Buffer prefix_;  // scratch: per front layer row, its prefix counts
  size_t prefixSize_ = 0;
  gl::Buffer covered_;  // scratch: the splatted view's depth bits per pixel
  size_t coveredSize_ = 0;
};

}  // namespace mvr
