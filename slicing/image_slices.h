#pragma once
// Image-based slicing (de Quilletes 2018, over Halle's slice table): every
// covered pixel of a source layer becomes a slice. Source and target views
// share the image-plane window and the row's camera y, so a pixel of
// scanline j stays on scanline j in every view: its EPI track is known
// from its 3D position alone, and the same EPI rasterizers draw it, with
// the depth test resolving overlaps between pixels and layers.
//
// A pixel's slice spans its footprint at its own depth, widened by
// `overlap` pixels on each side so that neighbours at slightly different
// depths do not open one-pixel cracks as the view moves away from the
// source; the depth test settles the overlap.
#include <vector>

#include "mvr/camera.h"
#include "mvr/source_layers.h"
#include "slicing/slice_table.h"

namespace mvr {

struct ImageSlices {
  ExtremeVertices vertices;  // two per slice; "triangle" k is slice k
  SliceTable table;
};

ImageSlices sliceSourceLayers(const std::vector<SourceLayer>& layers, const ShearingCamera& camera,
                              int row, float overlap = 0.25f);

}  // namespace mvr
