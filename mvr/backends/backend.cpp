#include "mvr/backends/backend.h"

#include <vector>

#include "mvr/backends/deferred/deferred_renderer.h"
#include "mvr/backends/mvr/mvr_renderer.h"
#include "mvr/backends/svr/svr_renderer.h"
#include "mvr/error.h"
#include "mvr/gl/gl_api.h"

namespace mvr {

std::unique_ptr<Renderer> makeRenderer(const BackendOptions& o, const Scene& scene, PixelType type) {
  switch (o.backend) {
    case Backend::Mvr: return makeMvrRenderer(scene, o.mvr.mode, type, o.mvr.texture, o.mvr.builder);
    case Backend::Interp: return makeInterpRenderer(scene, type, o.interp);
    case Backend::Warp: return makeWarpRenderer(scene, type, o.warp);
    case Backend::Svr: return makeSvrRenderer(scene, type);
    case Backend::SvrLayered: return makeLayeredSvrRenderer(scene, type);
    case Backend::Deferred: return makeDeferredRenderer(scene, type);
  }
  fail("--backend", "unknown back end");
}

PstMode fastestPst(const BackendOptions& o, const Scene& scene) {
  return gl::rendersOnCpu() ? PstMode::Cpu : fastestGpuPst(o, shading::planShading(scene));
}

PstMode fastestGpuPst(const BackendOptions& o, const shading::ShadingPlan& plan) {
  // What the span rasterizer accepts (epi/gpu/gpu_span_rasterizer.cpp):
  // mvr's one diffuse pass, or interp's slices coloured by texture
  // vectors without split highlight tracks.
  const bool spans = o.backend == Backend::Interp ? !(o.interp.splits > 0 && plan.specular)
                                                  : plan.passes().size() == 1;
  return spans ? PstMode::Spans : o.pst();
}

namespace {

std::vector<std::string> fields(const std::string& s) {
  std::vector<std::string> out;
  for (size_t at = 0;;) {
    const size_t next = s.find(':', at);
    out.push_back(s.substr(at, next == std::string::npos ? std::string::npos : next - at));
    if (next == std::string::npos) return out;
    at = next + 1;
  }
}

// NAME-psts names a PST builder.
bool builderOption(const std::string& token, PstBuilder& builder) {
  for (const auto& b : kPstBuilderNames)
    if (token == std::string(b.name) + "-psts") {
      builder = b.value;
      return true;
    }
  return false;
}

// One interp option token: a builder, a PST mode, a blend, or an entry of
// interp's tables. Values are checked where every interp option is
// (validate(InterpOptions)), not here.
void interpOption(const std::string& token, InterpOptions& o, const char* where) {
  if (builderOption(token, o.builder)) return;
  for (const auto& mode : kPstModeNames)
    if (token == mode.name) {
      o.mode = mode.value;
      return;
    }
  for (const auto& blend : kBlendNames)
    if (token == blend.name) {
      o.blend = blend.value;
      return;
    }
  if (!parseSpecToken<InterpOptions>(token, kInterpNumbers, kInterpFlags, o))
    fail(where, "unknown interp option '" + token + "'");
}

// One warp option token: a path, or an entry of warp's table; checked by
// validate(WarpOptions).
void warpOption(const std::string& token, WarpOptions& o, const char* where) {
  if (token == "cpu" || token == "gl") {
    o.path = token == "cpu" ? WarpPath::Cpu : WarpPath::Gl;
    return;
  }
  if (!parseSpecToken<WarpOptions>(token, kWarpNumbers, {}, o)) fail(where, "unknown warp option '" + token + "'");
}

// One mvr option token: a texture mode, or NAME-psts for a PST builder.
void mvrOption(const std::string& token, MvrOptions& o, const char* where) {
  if (builderOption(token, o.builder)) return;
  o.texture = parseName(kTextureModeNames, token, where, "mvr option");
}

}  // namespace

BackendOptions parseBackendSpec(const std::string& spec, const char* where) {
  const std::vector<std::string> field = fields(spec);
  BackendOptions o;
  o.backend = parseName(kBackendNames, field[0], where, "back end");
  if (o.backend == Backend::Interp) {
    if (field.size() > 1) o.interp.acquire = parseName(kAcquireNames, field[1], where, "acquisition");
    for (size_t i = 2; i < field.size(); ++i) interpOption(field[i], o.interp, where);
    validate(o.interp);
  } else if (o.backend == Backend::Warp) {
    if (field.size() > 1) o.warp.acquire = parseName(kAcquireNames, field[1], where, "acquisition");
    for (size_t i = 2; i < field.size(); ++i) warpOption(field[i], o.warp, where);
    validate(o.warp);
  } else if (o.hasPst()) {
    if (field.size() > 1) o.mvr.mode = parseName(kPstModeNames, field[1], where, "mode");
    for (size_t i = 2; i < field.size(); ++i) mvrOption(field[i], o.mvr, where);
  } else if (field.size() > 1) {
    fail(where, "'" + spec + "': " + field[0] + " takes no options");
  }
  return o;
}

}  // namespace mvr
