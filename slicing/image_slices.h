#pragma once
// Image-based slicing (de Quilletes 2018, over Halle's slice table): the
// covered pixels of a source layer become slices. Source and target views
// share the image-plane window and the row's camera y, so a pixel of
// scanline j stays on scanline j in every view: its EPI track is known
// from its 3D position alone, and the same EPI rasterizers draw it, with
// the depth test resolving overlaps between pixels and layers.
//
// A slice spans its pixels' footprint on the surface. Toward a neighbour
// of the same surface it ends on the boundary the two share, at the mean
// of their centres' depths, where the neighbour's slice ends too: the two
// meet in every view, so no crack opens as the view moves away from the
// source and neither covers the other's pixel. Neighbours are of one
// surface when over the track they move apart by at most 2 x `overlap`
// pixels (the measure coalescing uses). Toward an empty pixel or across a
// depth step the slice ends on its pixel's boundary: silhouettes stay
// where the source saw them instead of growing in every view (issue 18).
// At the image's edge it widens by `overlap` pixels, as the surface may go
// on beyond it. (Until issue 18's sixth step joined sides overlapped by
// `overlap` instead: the nearer of two neighbours then took a quarter
// pixel of the other's colour.)
// A lone pixel between two
// neighbours of its surface lies on their tangent (its depth slope the
// central difference), so where another view grazes the surface its
// footprint shrinks as the surface does instead of standing out of the
// silhouette at its full width. Its colours are a 1-D
// texture vector of its pixels (Halle 6.5.3): a slice's screen parameter
// names the same surface point in every view, so the run's pixels, taken
// at their source-view screen positions, are already that vector.
//
// Coalescing: a run of 2^l neighbouring pixels (an aligned block of a 1-D
// min/max depth mip) becomes one slice when its depths are so close that
// drawing it as one straight slice moves no pixel more than `coalesce`
// pixels in any view of the track. Window depth is affine in 1/w, and a
// pixel whose 1/w strays by e from the slice moves by e D |E - S| W / Wp
// pixels in the view at eye E (source eye S, image plane at distance D,
// W pixels across the plane width Wp). Specular pixels with split tracks
// never coalesce: their highlights differ.
#include <vector>

#include "mvr/camera.h"
#include "mvr/views/source_layers.h"
#include "slicing/slice_table.h"

namespace mvr {

struct ImageSliceOptions {
  float overlap = 0.25f;  // neighbours join within 2x this drift, pixels; the widening at the image's edge
  float coalesce = 0.0f;  // largest added displacement, pixels; 0: a slice per pixel
  // Split tracks for highlights (slicing/highlight_splits.h): with a scene
  // and layers that carry normals, every pixel of a specular material is
  // its own slice with knots from `splits` split views per light.
  const Scene* scene = nullptr;
  int splits = 0;
  // Scanlines per task: bands are sliced in parallel and joined in
  // scanline order, so the table is the same for any band size.
  int bandRows = 8;
  // Slices meet the nearest other source's outline in its view
  // (LayerSlicer::meetOtherOutline).
  bool meetSilhouettes = true;
  // A lone pixel at a smooth silhouette ends at the outline and depth its
  // surface's curvature gives (LayerSlicer::rimFit). Measured to help only
  // where two sources' outlines are blended (mvr/backends/interp/source_blend.h).
  bool fitRims = false;
};

struct ImageSlices {
  ExtremeVertices vertices;  // two per slice; "triangle" k is slice k, with its vector
  SliceTable table;
  size_t pixels = 0;  // covered source pixels the slices carry
  std::vector<uint32_t> layerOf;  // per slice, the index of its layer
};

ImageSlices sliceSourceLayers(const std::vector<SourceLayer>& layers, const ShearingCamera& camera,
                              int row, const ImageSliceOptions& options = {});

// Per layer (eyes: each layer's source eye, a source's layers together,
// front first), the index of the front layer of the nearest source at
// another eye, or -1: whose outline its slices meet (meetSilhouettes).
// candidates: per layer, whether its source may be chosen, by its front
// layer's flag (empty: all; a GPU store holds sources a slicing leaves out).
std::vector<int> nearestOtherSource(const std::vector<glm::dvec2>& eyes, const std::vector<uint8_t>& candidates = {});

// Per layer (as nearestOtherSource's eyes), the index of its source's
// nearest layer: the first of the run of layers with its eye.
std::vector<int> nearestLayerOf(const std::vector<glm::dvec2>& eyes);

// The window-depth range a coalesced run may span from a source eye at
// camera x `eyeX` (infinite when the track has no width).
float coalesceDepthRange(const ShearingCamera& camera, double eyeX, float pixels);

}  // namespace mvr
