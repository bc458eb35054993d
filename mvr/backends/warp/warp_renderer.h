#pragma once
// The depth-image warping back end (seed 003; mvr/backends/warp/depth_warp.h): each
// view composited from its two nearest RGB-D references. References come
// from a scene, rendered by the deferred pipeline at source eyes on the
// track (as interp's sources), or from a capture (mvr synthesize).
#include <memory>
#include <vector>

#include "mvr/names.h"
#include "mvr/renderer.h"
#include "mvr/rgbd_view.h"
#include "mvr/scene.h"
#include "mvr/views/acquire.h"

namespace mvr {

enum class WarpPath { Auto, Gl, Cpu };
inline constexpr NameTable<WarpPath, 3> kWarpPathNames{
    {{WarpPath::Auto, "auto"}, {WarpPath::Gl, "gl"}, {WarpPath::Cpu, "cpu"}}};

struct WarpOptions {
  // dual: both ends of the track; hierarchical: then the view halfway
  // between two sources wherever only their labelled rubber sheets cover
  // more than holeFraction of the pixels, breadth first within budget.
  Acquire acquire = Acquire::Dual;
  // Relative depth step, of the nearer depth, that makes a discontinuity
  // (occlusion label) and a nearer surface (visibility test). A smooth
  // surface tilted by alpha steps (Wp / (W D)) tan(alpha) between pixels:
  // with the bundled cameras (Wp / D = 1/2) 0.08% tan(alpha) at 640 pixels
  // across, so 0.02 labels no smooth surface tilted less than 87 degrees
  // (81 at 160 pixels), while objects that occlude one another stand off
  // by much more than 2% of their depth.
  float tau = 0.02f;
  float penalty = 30.0f;  // a of eq. 5-2, the seed's value for its datasets
  // Pixels a vertex of a reference's grid may move, in the farthest view
  // the reference serves, where grid cells on a near-plane merge into one
  // quad (GridTriangles, mvr/backends/warp/depth_warp.cpp): fewer triangles a view
  // (a CPU GL pays per triangle) against the surface's curvature inside a
  // quad. 0: only planes merge. Measured (docs/BENCHMARKS.md).
  float flatness = 0.15f;
  int budget = 9;         // hierarchical: source views per row at most
  // Where views are warped: by GL (the seed's grid mesh, view order) or on
  // the CPU (mvr/backends/warp/warp_spans.h: exact segments, EPI order; scene sources,
  // or references on the rows of the track, makeWarpRenderer). Auto: the
  // CPU where GL itself renders on the CPU (llvmpipe) and it can take the
  // references, measured faster there at every size (docs/BENCHMARKS.md);
  // else GL.
  WarpPath path = WarpPath::Auto;
  double holeFraction = 1e-3;
};

// Throws mvr::Error naming the option that is out of range; needs no GL.
void validate(const WarpOptions& options);

// Needs a current GL context.
std::unique_ptr<Renderer> makeWarpRenderer(const Scene& scene, PixelType type, const WarpOptions& options);
// Views of a capture: every reference must have the same size. track: the
// views it will render, if known: where every row of them has references
// on it (each the view of track's camera at its eye on that row, as our
// sets and the HCI layout are), the CPU warp can take them.
std::unique_ptr<Renderer> makeWarpRenderer(std::vector<RgbdView> references, PixelType type,
                                           const WarpOptions& options, const ShearingCamera* track = nullptr);

}  // namespace mvr
