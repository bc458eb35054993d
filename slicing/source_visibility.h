#pragma once
// How source pixels move along the camera track, and two uses of it in the
// image-based back end (de Quilletes 2018):
//  - conservative visibility: a pixel of a deeper layer is dropped when the
//    nearest layer covers it from every view of the track (image-space
//    erosion with a radius that grows with the depth gap);
//  - hole estimation: splatting the source layers into a view between two
//    sources shows where they leave disocclusion gaps (hierarchical
//    acquisition adds a source view there).
//
// A source pixel at window depth d, seen from camera x S, lies in the view
// at camera x E shifted by (E - S)(1 - D/w) W / Wp pixels, where 1/w is
// affine in d: 1/w = (d (f - n) + n) / (n f) (reversed Z, near n, far f).
#include <vector>

#include "mvr/camera.h"
#include "mvr/views/source_layers.h"

namespace mvr {

class TrackParallax {
 public:
  explicit TrackParallax(const ShearingCamera& cam);
  // Pixels a pixel at window depth d moves from camera x `from` to `to`.
  double shift(float depth, double from, double to) const;
  // Pixels per unit of window depth difference per unit of camera x.
  double pixelsPerDepth() const { return pixelsPerDepth_; }
  // The largest distance from camera x to a view of the track.
  double reach(double x) const;

 private:
  const ShearingCamera& cam_;
  double pixelsPerDepth_;
};

// Drops (sets to depth 0) the pixels of `back`, a deeper layer seen from
// the same eye as `front`, the nearest layer, that `front` hides from every
// view of the track: `front` covers the pixels around it out to the largest
// motion of the back pixel against any front pixel, and no crack wider
// than the slices' overlap opens between neighbouring front pixels.
// Returns the back pixels that remain.
long hideInvisible(const SourceLayer& front, SourceLayer& back, const ShearingCamera& cam,
                   float overlap);

// Disocclusion holes the layers leave in the view at camera x `eyeX`:
// empty pixels there with covered pixels on both sides of the same
// scanline no further apart than the widest gap the layers' depth range
// can open between their sources and eyeX. Whatever fills such a pixel
// lies at about the depth of one of the gap's sides; it is a hole when
// every source's nearest layer is covered where that depth puts it (were
// it background, some source would see background there). Slices are
// splatted as the rasterizers draw them (footprints widened by `overlap`).
long countHoles(const std::vector<const SourceLayer*>& layers, const ShearingCamera& cam,
                double eyeX, float overlap);

}  // namespace mvr
