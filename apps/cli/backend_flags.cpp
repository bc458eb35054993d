#include "apps/cli/backend_flags.h"

#include "mvr/error.h"

namespace mvr::app {
// warp's numbers that interp's table declares too were added once, as
// interp's options (add): given on the command line, they are warp's values.
void BackendFlags::copyShared(BackendOptions& o) const {
  for (const NumberOption<WarpOptions>& w : kWarpNumbers)
    for (const CLI::Option* option : interpOptions_)
      if (option->check_name(w.flag) && option->count()) w.set(o.warp, option->as<double>());
}

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
  WarpOptions& warp = options_.warp;
  // The tables' numbers and switches (interp_options.h, warp_options.h); a
  // flag both back ends declare (--budget) is added once, bound to
  // interp's member, and copied to warp's by resolve().
  for (const NumberOption<InterpOptions>& n : kInterpNumbers) interpOptions_.push_back(addNumber(app, n, interp));
  for (const FlagOption<InterpOptions>& f : kInterpFlags)
    interpOptions_.push_back(app.add_flag_function(
        f.flag, [&interp, f](std::int64_t) { interp.*f.member = f.value; }, f.help));
  for (const NumberOption<WarpOptions>& n : kWarpNumbers)
    if (!app.get_option_no_throw(n.flag)) warpOptions_.push_back(addNumber(app, n, warp));
  warpOptions_.push_back(app.add_option("--warp-path", warpPath_,
                                        "warp: by GL, the seed's grid mesh (gl), or on the CPU, EPI by EPI, exactly "
                                        "(cpu; scene sources only); auto (default): cpu where GL renders on the CPU "
                                        "(llvmpipe), else gl")
                             ->type_name(choices(kWarpPathNames)));
  interpOptions_.push_back(app.add_option("--blend", blend_,
                                          "interp: between two sources, let the depth test pick one per pixel "
                                          "(none, default) or weight both where they agree, by distance along the "
                                          "track (track) or by the angles at the pixel (angular); blending draws "
                                          "each interval 3 times")
                               ->type_name(choices(kBlendNames)));
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
  // Which back ends an option applies to: interp's, warp's, or both
  // (--acquire, and the numbers both tables declare).
  auto isWarps = [&](const CLI::Option* option) {
    for (const NumberOption<WarpOptions>& n : kWarpNumbers)
      if (option->check_name(n.flag)) return true;
    return false;
  };
  for (const CLI::Option* option : interpOptions_)
    if (option->count() && o.backend != Backend::Interp && !(isWarps(option) && o.backend == Backend::Warp))
      fail(option->get_name(), isWarps(option) ? "applies to --backend interp and warp only"
                                               : "applies to --backend interp only");
  for (const CLI::Option* option : warpOptions_)
    if (option->count() && o.backend != Backend::Warp)
      fail(option->get_name(), "applies to --backend warp only");
  if (acquireOption_->count() && o.backend != Backend::Interp && o.backend != Backend::Warp)
    fail(acquireOption_->get_name(), "applies to --backend interp and warp only");
  if (o.backend == Backend::Interp) {
    if (!acquire_.empty()) o.interp.acquire = parseAcquire(acquire_);
    if (!blend_.empty()) o.interp.blend = parseName(kBlendNames, blend_, "--blend", "blend");
    validate(o.interp);
  }
  if (o.backend == Backend::Warp) {
    if (!acquire_.empty()) o.warp.acquire = parseAcquire(acquire_);
    copyShared(o);
    if (!warpPath_.empty()) o.warp.path = parseName(kWarpPathNames, warpPath_, "--warp-path", "path");
    // The GL path warps the seed's grid mesh: its silhouettes end at pixel
    // boundaries, as one sample a pixel does; finer needs the CPU's.
    for (const CLI::Option* option : interpOptions_)
      if (o.warp.path == WarpPath::Gl && option->check_name("--outline-samples") && option->count() &&
          option->as<int>() != 1)
        fail("--outline-samples", "above 1 needs warp's cpu path: --warp-path gl ends silhouettes at pixel edges");
    validate(o.warp);
  }
  return o;
}

}  // namespace mvr::app
