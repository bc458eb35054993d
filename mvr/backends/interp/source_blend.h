#pragma once
// Blending two source views where both see the scene, instead of letting
// the depth test pick one per pixel (issue 18, deliverable 3).
//
// The views between two neighbouring sources A and B are drawn three
// times: from both sources' slices together (the depth test resolves
// occlusion: the joint EPI), and from each source's slices alone. Per
// pixel of the joint EPI, with w the weight of A in that view and 1 - w
// that of B:
//   - both cover it with colours that agree (one surface seen twice): the
//     mix w A + (1 - w) B;
//   - one covers it and the other sees background there (its empty run
//     reaches the EPI row's end or a pixel neither source covers): the
//     joint colour at the covering source's weight as coverage. Each source's
//     outline is exact at its own eye only and is rounded to whole
//     pixels; the depth-tested union of two rounded outlines stands out
//     of the true silhouette (issue 18: 60-90 extra pixels a bunny view,
//     even one view from a source on either side), and weighting the
//     disagreement between them instead anti-aliases the silhouette;
//   - elsewhere the joint pixel: occlusion, cracks, holes.
#include "mvr/camera.h"
#include "mvr/image.h"
#include "mvr/names.h"

namespace mvr {

// How the views between two sources combine them:
//   none     winner takes all: the depth test picks a source per pixel
//   track    weights linear in the eye's distance along the track
//   angular  the cosine form of the depth-image warp's angular weight
//            (mvr/backends/warp/depth_warp.h), from the angles the eyes make at the
//            pixel's point on the image plane
enum class Blend { None, Track, Angular };
inline constexpr NameTable<Blend, 3> kBlendNames{
    {{Blend::None, "none"}, {Blend::Track, "track"}, {Blend::Angular, "angular"}}};

// The weight of source A in view `view` of `interval` (a camera whose first
// view is A's eye and whose last is B's) at pixel (x, scanline); B's is one
// minus it. 1 at A, 0 at B.
double sourceWeight(Blend mode, const ShearingCamera& interval, int row, int scanline, int view, int x);

// Blends one EPI in place, as above: `joint` is both sources' EPI, `a` and
// `b` each source's alone, all of one size, their rows the interval's
// views from `firstView` on.
void blendEpi(Blend mode, const ShearingCamera& interval, int row, int scanline, const Image& a, const Image& b,
              Image& joint, int firstView = 0);

}  // namespace mvr
