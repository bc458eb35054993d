#pragma once
// The image-based back end's slicing (slicing/image_slices.h) as compute
// passes over source layers that never leave GPU memory (DeviceLayers): the
// same slices, in the same scanline order, with the same endpoints and
// texture vectors as sliceSourceLayers, its CPU oracle.
//
// Every pixel decides on its own whether it starts a run: with coalescing,
// the runs the CPU's greedy walk picks are exactly the maximal aligned
// blocks whose depths agree, so a pixel starts one when the largest such
// block holding it starts at it (a per-level min/max depth mip answers
// that in one read per level). A prefix sum over the start flags, in
// (scanline, layer, x) order, gives each run its slot in the slice table;
// the same pass then writes its slice, its two endpoint records, its
// "triangle" and its vector. Only the height + 1 offsets and the covered
// pixel count come back to the host.
//
// Endpoints: a pixel at window (x, y, d) seen from camera x S lies, in the
// view at camera x C, at x + (S - C) (W / Wp) Z / w, with Z / w = D / w - 1
// affine in d: the extreme-view transform of ExtremeTransform folded into
// one multiply-add per endpoint.
#include <cstddef>

#include "mvr/camera.h"
#include "mvr/gl/gl_handles.h"
#include "mvr/gl/prefix_sum.h"
#include "mvr/views/source_layers.h"
#include "slicing/gpu/gpu_slice_table.h"
#include "slicing/gpu/gpu_vertices.h"
#include "slicing/image_slices.h"

namespace mvr {

struct GpuImageSlices {
  GpuVertices vertices;  // two per slice; "triangle" k is slice k, with its vector
  GpuSliceTable table;
  size_t pixels = 0;  // covered source pixels the slices carry
};

class GpuImageSlicer {
 public:
  GpuImageSlicer();  // needs a current GL context

  // The slices of every layer in `layers` for the row of views they were
  // seen from (source and target views share its camera y: y stays put).
  // options.scene and splits are not supported (highlights split on the
  // CPU); throws mvr::Error if set. With coalescing off, the vectors index
  // the layers' colour buffer itself, which must outlive the draws.
  // keep: per layer of the store, whether its pixels become slices (the
  // others still serve as outlines to meet); empty: all. order: the
  // store's layers in the order a scanline's slices follow (every layer
  // once; empty: the store's), as the host slices its list of layers in
  // order: the rasterizers keep the first of equal depths.
  GpuImageSlices build(const DeviceLayers& layers, const ShearingCamera& cam, const ImageSliceOptions& options,
                       const std::vector<uint8_t>& keep = {}, const std::vector<int>& order = {});

 private:
  gl::Program mip_, flag_, fill_;
  gl::PrefixSum prefixSum_;
  gl::Buffer flags_, mips_;  // scratch, kept across rows
  size_t flagsSize_ = 0, mipsSize_ = 0;
};

}  // namespace mvr
