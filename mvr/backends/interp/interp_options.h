#pragma once
// interp's options: each declared once here with its default, and checked
// before any GL work (validate).
#include <string>

#include "epi/epi_rasterizer.h"
#include "mvr/backends/interp/source_blend.h"
#include "mvr/names.h"
#include "mvr/option_table.h"
#include "mvr/views/acquire.h"

namespace mvr {

struct InterpOptions {
  Acquire acquire = Acquire::Dual;
  int maxLayers = 4;        // depth-peeled layers per source view
  PstMode mode = PstMode::Quad;  // exact for image slices in every mode
  // GL modes: where image slices and PSTs are built. On the GPU the source
  // layers stay in GPU memory (without splits or blending; those slice on
  // the CPU, PSTs still pulled); with visibility or hierarchical
  // acquisition only where GL runs on a GPU, or with Gpu named.
  PstBuilder builder = PstBuilder::Auto;
  float overlap = 0.25f;    // pixels: neighbours join within 2x this drift (ImageSliceOptions)
  float coalesce = 0.0f;    // pixels a coalesced run may move a pixel; 0: off
  // Drop layer pixels the nearest layer hides from the whole track, and
  // stop peeling at a layer with none left (a heuristic: a deeper layer
  // could still show where this one is hidden).
  bool visibility = false;
  int budget = 9;           // hierarchical: source views per row at most
  // Specular highlights: 0 bakes them into the source pixels as their
  // source eye saw them; K > 0 splits each specular pixel's track at K
  // views across the highlight (slicing/highlight_splits.h). A scene
  // without specular materials ignores it.
  int splits = 0;
  // How the views between two sources combine them (mvr/backends/interp/source_blend.h):
  // none lets the depth test pick one source per pixel; track and angular
  // weight both where they agree, drawing each interval three times.
  Blend blend = Blend::None;
  // hierarchical: holes a view between two sources may show, as a
  // fraction of the image's pixels, before a source is added there
  // (negative: at every halfway view, until the budget is spent).
  double holeFraction = 1e-3;
  // Columns a pixel each source's nearest layer is sampled at for its
  // outline (SourceLayer::outline): slices at a silhouette end where the
  // surface does, within the pixel, instead of on its boundary. 1: off.
  // 8: the bunny at 160x120 x 16 scored 31.6 dB at 4, 32.2 at 8, 32.0 at
  // 16 (the outline pass drawn 8 times as wide costs 7% more there).
  int outlineSamples = 8;
  // Each half of an interval between two sources from its near source's
  // layers and the far source's nearest layer (false: every layer of both
  // over the whole interval; blending always draws it whole).
  bool halves = true;
  // Each source's layers from one pass of the mesh into per-pixel fragment
  // lists (mvr/views/fragment_lists.h; false: a pass of the mesh per
  // layer, with no lists' memory). The same layers either way.
  bool onePass = true;
};

// interp's numbers and switches: flag, key in a bench spec
// (interp:ACQUIRE:KEY VALUE...), member, range, help (mvr/option_table.h).
inline const NumberOption<InterpOptions> kInterpNumbers[] = {
    {"--max-layers", "", &InterpOptions::maxLayers, 1, 64, false, "", "interp: depth-peeled layers per source view"},
    {"--coalesce", "c", &InterpOptions::coalesce, 0, kUnbounded, false, "T",
     "interp: draw runs of source pixels with close depths as one slice when that moves no pixel more than T "
     "pixels in any view (0: a slice per pixel)"},
    {"--budget", "b", &InterpOptions::budget, 2, 1024, false, "", "interp and warp hierarchical: source views per row at most"},
    {"--splits", "s", &InterpOptions::splits, 0, 64, false, "K",
     "interp: highlights per view, split at K views across each specular pixel's highlight (0: as the source "
     "saw it)"},
    {"--overlap", "o", &InterpOptions::overlap, 0, 4, false, "P",
     "interp: join neighbouring pixels whose tracks part by at most 2P pixels over the track (joined, they "
     "share their boundary's end: no cracks); slices at the image's edge widen by P"},
    {"--outline-samples", "x", &InterpOptions::outlineSamples, 1, 16, false, "S",
     "interp and warp on the cpu: sample each source's outline at S columns a pixel (its nearest layer drawn once "
     "more, S times as wide) so that silhouettes end where the surface does, within a sample (1: at the pixel's "
     "boundary)"},
};
inline const FlagOption<InterpOptions> kInterpFlags[] = {
    {"--visibility", "vis", &InterpOptions::visibility, true,
     "interp: drop layer pixels the nearest layer hides from the whole track; stop peeling at a layer with none "
     "left"},
    {"--whole-intervals", "whole", &InterpOptions::halves, false,
     "interp: draw the views between two sources from every layer of both, not each half from its near "
     "source's layers and the far source's nearest layer"},
    {"--layer-passes", "passes", &InterpOptions::onePass, false,
     "interp: draw the mesh once per depth-peeled layer instead of once per source into per-pixel fragment "
     "lists (the same layers, without the lists' memory)"},
};

// Throws mvr::Error naming the option that is out of range; needs no GL.
inline void validate(const InterpOptions& options) { checkRanges<InterpOptions>(kInterpNumbers, options); }

}  // namespace mvr
