#include "apps/backend_flags.h"

#include "mvr/error.h"

namespace mvr::app {

void BackendFlags::add(CLI::App& app) {
  InterpOptions& interp = options_.interp;
  app.add_option("--backend", backend_, "renderer")
      ->type_name(choices(kBackendNames))
      ->capture_default_str();
  app.add_option("--pst", pst_,
                 "accuracy mode of mvr and interp: " + alternatives(kPstModeNames) +
                     " (default: cpu where GL renders on the CPU (llvmpipe), else spans where they "
                     "shade the scene, else mvr " +
                     pstModeName(MvrOptions{}.mode) + ", interp " + pstModeName(InterpOptions{}.mode) + ")")
      ->type_name(choices(kPstModeNames));
  textureOption_ = app.add_option("--texture", texture_,
                                  "mvr texturing: 1-D texture vectors per slice (vector, default) or "
                                  "the 2D texture with a per-pixel divide (direct)")
                       ->type_name(choices(kTextureModeNames));
  builderOption_ = app.add_option("--pst-builder", builder_,
                                  "mvr and interp GL modes: slice and build PST geometry on the GPU (gpu) "
                                  "or on the CPU, uploaded per batch (cpu); auto (default): gpu unless GL "
                                  "renders on the CPU (llvmpipe)")
                       ->type_name(choices(kPstBuilderNames));
  acquireOption_ = app.add_option("--acquire", acquire_,
                                  "interp and warp: source views from the middle of the track (center, "
                                  "interp only), both ends (dual), or both ends and then halfway between "
                                  "two sources wherever they leave holes, recursively (hierarchical); "
                                  "default " + std::string(acquireName(interp.acquire)))
                       ->type_name(choices(kAcquireNames));
  budgetOption_ = app.add_option("--budget", interp.budget,
                                 "interp and warp hierarchical: source views per row at most")
                      ->capture_default_str();
  WarpOptions& warp = options_.warp;
  warpOptions_ = {
      app.add_option("--tau", warp.tau,
                     "warp: relative depth step that makes a depth discontinuity (occlusion label) "
                     "and a nearer surface (visibility test)")
          ->capture_default_str(),
      app.add_option("--penalty", warp.penalty,
                     "warp: growth a of the occlusion penalty phi = occ (a theta_i / (theta_i + "
                     "theta_j))^4")
          ->type_name("A")
          ->capture_default_str(),
      app.add_option("--flatness", warp.flatness,
                     "warp by GL: merge a reference's grid cells into one quad where that moves no vertex more than "
                     "PX pixels in the farthest view (0: only planes merge)")
          ->type_name("PX")
          ->capture_default_str(),
      app.add_option("--warp-path", warpPath_,
                     "warp: by GL, the seed's grid mesh (gl), or on the CPU, EPI by EPI, exactly (cpu; scene "
                     "sources only); auto (default): cpu where GL renders on the CPU (llvmpipe), else gl")
          ->type_name(choices(kWarpPathNames)),
  };
  interpOptions_ = {
      app.add_option("--max-layers", interp.maxLayers, "interp: depth-peeled layers per source view")
          ->capture_default_str(),
      app.add_option("--coalesce", interp.coalesce,
                     "interp: draw runs of source pixels with close depths as one slice when that "
                     "moves no pixel more than T pixels in any view (0: a slice per pixel)")
          ->type_name("T")
          ->capture_default_str(),
      app.add_flag("--visibility", interp.visibility,
                   "interp: drop layer pixels the nearest layer hides from the whole track; stop "
                   "peeling at a layer with none left"),
      app.add_option("--splits", interp.splits,
                     "interp: highlights per view, split at K views across each specular pixel's "
                     "highlight (0: as the source saw it)")
          ->type_name("K")
          ->capture_default_str(),
      app.add_option("--blend", blend_,
                     "interp: between two sources, let the depth test pick one per pixel (none, "
                     "default) or weight both where they agree, by distance along the track (track) "
                     "or by the angles at the pixel (angular); blending draws each interval 3 times")
          ->type_name(choices(kBlendNames)),
      app.add_option("--overlap", interp.overlap,
                     "interp: join neighbouring pixels whose tracks part by at most 2P pixels over "
                     "the track (joined, they share their boundary's end: no cracks); slices at the "
                     "image's edge widen by P")
          ->type_name("P")
          ->capture_default_str(),
      app.add_flag("--whole-intervals", wholeIntervals_,
                   "interp: draw the views between two sources from every layer of both, not each "
                   "half from its near source's layers and the far source's nearest layer"),
      app.add_flag("--layer-passes", layerPasses_,
                   "interp: draw the mesh once per depth-peeled layer instead of once per source "
                   "into per-pixel fragment lists (the same layers, without the lists' memory)"),
      app.add_option("--outline-samples", interp.outlineSamples,
                     "interp: sample each source's outline at S columns a pixel (its nearest layer "
                     "drawn once more, S times as wide) so that silhouettes end where the surface "
                     "does, within a sample (1: at the pixel's boundary)")
          ->type_name("S")
          ->capture_default_str(),
  };
}

void BackendFlags::chooseDefaultPst(BackendOptions& o, const Scene& scene) const {
  if (o.hasPst() && !pst_ && !textureOption_->count() && !builderOption_->count()) o.setPst(fastestPst(o, scene));
}

BackendOptions BackendFlags::resolve() const {
  BackendOptions o = options_;
  o.backend = parseName(kBackendNames, backend_, "--backend", "back end");
  if (pst_) {
    if (!o.hasPst()) fail("--pst", "applies to --backend mvr and interp only");
    o.setPst(parsePstMode(*pst_));
  }
  if (textureOption_->count()) {
    if (o.backend != Backend::Mvr) fail("--texture", "applies to --backend mvr only");
    o.mvr.texture = parseTextureMode(texture_);
  }
  if (builderOption_->count()) {
    if (!o.hasPst()) fail("--pst-builder", "applies to --backend mvr and interp only");
    o.setBuilder(parseName(kPstBuilderNames, builder_, "--pst-builder", "builder"));
  }
  for (const CLI::Option* option : interpOptions_)
    if (option->count() && o.backend != Backend::Interp)
      fail(option->get_name(), "applies to --backend interp only");
  for (const CLI::Option* option : warpOptions_)
    if (option->count() && o.backend != Backend::Warp)
      fail(option->get_name(), "applies to --backend warp only");
  for (const CLI::Option* option : {acquireOption_, budgetOption_})
    if (option->count() && o.backend != Backend::Interp && o.backend != Backend::Warp)
      fail(option->get_name(), "applies to --backend interp and warp only");
  if (o.backend == Backend::Interp) {
    if (!acquire_.empty()) o.interp.acquire = parseAcquire(acquire_);
    if (!blend_.empty()) o.interp.blend = parseName(kBlendNames, blend_, "--blend", "blend");
    if (wholeIntervals_) o.interp.halves = false;
    if (layerPasses_) o.interp.onePass = false;
    validate(o.interp);
  }
  if (o.backend == Backend::Warp) {
    if (!acquire_.empty()) o.warp.acquire = parseAcquire(acquire_);
    if (budgetOption_->count()) o.warp.budget = o.interp.budget;
    if (!warpPath_.empty()) o.warp.path = parseName(kWarpPathNames, warpPath_, "--warp-path", "path");
    validate(o.warp);
  }
  return o;
}

}  // namespace mvr::app
