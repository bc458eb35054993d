#pragma once
// warp's options: each declared once here with its default and range, and
// checked before any GL work (validate).
#include "mvr/names.h"
#include "mvr/option_table.h"
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
  // On the CPU, scene sources: columns a pixel each source's outline is
  // sampled at (InterpOptions::outlineSamples), and silhouette segments
  // end there instead of at the outermost pixel centre. 1: off. The GL
  // warp's grid has no place for them.
  int outlineSamples = 8;
};

// warp's numbers: flag, key in a bench spec (warp:ACQUIRE:KEY VALUE...),
// member, range, help (mvr/option_table.h).
inline const NumberOption<WarpOptions> kWarpNumbers[] = {
    {"--tau", "t", &WarpOptions::tau, 0, 1, true, "",
     "warp: relative depth step that makes a depth discontinuity (occlusion label) and a nearer surface "
     "(visibility test)"},
    {"--penalty", "a", &WarpOptions::penalty, 0, kUnbounded, false, "A",
     "warp: growth a of the occlusion penalty phi = occ (a theta_i / (theta_i + theta_j))^4"},
    {"--budget", "b", &WarpOptions::budget, 2, 1024, false, "", "interp and warp hierarchical: source views per row at most"},
    {"--flatness", "f", &WarpOptions::flatness, 0, 16, false, "PX",
     "warp by GL: merge a reference's grid cells into one quad where that moves no vertex more than PX pixels "
     "in the farthest view (0: only planes merge)"},
    {"--outline-samples", "x", &WarpOptions::outlineSamples, 1, 16, false, "S",
     "interp and warp on the cpu: sample each source's outline at S columns a pixel"},
};

// Throws mvr::Error naming the option that is out of range; needs no GL.
inline void validate(const WarpOptions& options) {
  if (options.acquire == Acquire::Center) fail("--acquire", "warp composites two references: dual or hierarchical");
  checkRanges<WarpOptions>(kWarpNumbers, options);
}

}  // namespace mvr
