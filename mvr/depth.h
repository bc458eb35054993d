#pragma once
// Depth maps of a rendered set (mvr render --depth), by every back end at
// its own speed and with its own coverage: the scene is rendered a second
// time with each vertex's colour set to its depth, unlit.
//
// Depth is the distance along the view axis, camera z of V
// (ShearingCamera::worldToCamera): D - Z for a point at world Z. The
// cameras of a shearing track share their plane and axis, so a point has
// the same depth in every view: it is a view-independent surface
// attribute like a diffuse colour, and affine in the point, so a
// perspective-correct (hyperbolic) interpolation of it is exact. The
// colour channel carries it normalised over the scene's vertex depths,
// c = (z - nearest) / range in [0, 1], so that no lighting clamp bites and
// the triangles clipped at the near or far plane interpolate the true
// values.
#include "mvr/camera.h"
#include "mvr/image.h"
#include "mvr/scene.h"

namespace mvr {

struct DepthColoring {
  double nearest = 0.0, range = 1.0;  // over the scene's vertices

  float colorOf(double depth) const { return float((depth - nearest) / range); }
  float depthOf(float color) const { return float(nearest + range * double(color)); }
};

// The scene's geometry with every vertex coloured by its depth under
// `cam`: one grey per vertex, materials white and matte with no texture or
// map (each keeps its culling), no lights, ambient 1, colours exact.
Scene depthScene(const Scene& scene, const ShearingCamera& cam, DepthColoring& coloring);

// A rendered view of the depth scene (F32) as depth: z where the view is
// covered (alpha above one half), 0 where nothing is seen.
DepthImage depthFromColors(const Image& view, const DepthColoring& coloring);

// A frame of the depth scene (F32: a view or an EPI) as its depths, packed
// one float a pixel into an image of type U8 (4 bytes a pixel) of the same
// size: the reorderers and a split job's exchange only move pixels, so
// depth goes through them at a quarter of the float colour's bytes, and
// 0 (nothing seen) where they leave a pixel unwritten. `packed` is reused.
constexpr PixelType kPackedDepth = PixelType::U8;
void packDepth(const Image& frame, const DepthColoring& coloring, Image& packed);
// A view packed so, as a depth map.
DepthImage unpackDepth(const Image& packed);

}  // namespace mvr
