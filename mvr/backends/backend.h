#pragma once
// The back ends a user chooses from, their typed options and the one
// factory. Every option's default is written once, in its options struct
// (MvrOptions here, InterpOptions in interp_renderer.h); render, stream,
// bench and the viewer fill these structs and call makeRenderer.
#include <memory>
#include <string>

#include "epi/epi_rasterizer.h"
#include "mvr/backends/interp/interp_renderer.h"
#include "mvr/backends/warp/warp_renderer.h"
#include "mvr/names.h"
#include "mvr/renderer.h"
#include "mvr/scene.h"
#include "shading/shading_plan.h"

namespace mvr {

enum class Backend { Mvr, Interp, Warp, Svr, SvrLayered, Deferred };
inline constexpr NameTable<Backend, 6> kBackendNames{{{Backend::Mvr, "mvr"},
                                                      {Backend::Interp, "interp"},
                                                      {Backend::Warp, "warp"},
                                                      {Backend::Svr, "svr"},
                                                      {Backend::SvrLayered, "svr-layered"},
                                                      {Backend::Deferred, "deferred"}}};

struct MvrOptions {
  PstMode mode = PstMode::Strip;
  TextureMode texture = TextureMode::Vector;  // GL modes; cpu samples directly
  PstBuilder builder = PstBuilder::Auto;      // GL modes
};

struct BackendOptions {
  Backend backend = Backend::Mvr;
  MvrOptions mvr;
  InterpOptions interp;
  WarpOptions warp;

  // mvr and interp fill EPIs through an accuracy mode; the baselines do not.
  bool hasPst() const { return backend == Backend::Mvr || backend == Backend::Interp; }
  // The chosen back end's accuracy mode (its own default unless set).
  PstMode pst() const { return backend == Backend::Interp ? interp.mode : mvr.mode; }
  void setPst(PstMode mode) { (backend == Backend::Interp ? interp.mode : mvr.mode) = mode; }
  void setBuilder(PstBuilder b) { (backend == Backend::Interp ? interp.builder : mvr.builder) = b; }
};

// Throws mvr::Error for options that cannot work (before any GL work where
// it can). GL back ends need a current context.
std::unique_ptr<Renderer> makeRenderer(const BackendOptions& options, const Scene& scene,
                                       PixelType type);

// The fastest accuracy mode that renders `options` over `scene` where the
// user named none: the CPU spans where GL renders on the CPU (llvmpipe:
// exact, and 3-10x the GL modes' speed there), else fastestGpuPst().
// Needs a current GL context.
PstMode fastestPst(const BackendOptions& options, const Scene& scene);
// On a GPU: the GPU spans where they shade the scene (mvr: a diffuse
// scene; interp: all but split highlights of a specular scene; an NVIDIA
// H100 drew 33x svr with spans against strip's 14x at 160x140), else the
// back end's own default.
PstMode fastestGpuPst(const BackendOptions& options, const shading::ShadingPlan& plan);

// The benchmark's compact form: NAME[:PST[:OPTION...]] with a texture mode
// or a PST builder (auto-psts, gpu-psts, cpu-psts) as options (mvr:exact:direct) or
// interp[:ACQUIRE[:OPTION...]] with options L (layers), cT (coalesce T
// pixels), vis (visibility), bB (budget), sK (splits), oP (overlap P
// pixels), a PST builder and an accuracy mode, e.g.
// interp:hierarchical:2:c0.5:vis:b5:exact, or
// warp[:ACQUIRE[:OPTION...]] with tT (tau), aA (penalty a), bB (budget).
// Throws naming `where` for an unknown name or option.
BackendOptions parseBackendSpec(const std::string& spec, const char* where = "--backends");

}  // namespace mvr
