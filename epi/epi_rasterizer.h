#pragma once
// One interface for every way of filling EPIs from a slice table: the GL
// rasterizer in three accuracy modes and the CPU span rasterizer.
#include <memory>
#include <string>

#include "mvr/names.h"
#include "mvr/renderer.h"
#include "shading/environment_set.h"
#include "shading/shading_plan.h"
#include "shading/texture_set.h"
#include "slicing/slice_table.h"
#include "slicing/gpu/gpu_vertices.h"
#include "slicing/slice_table_view.h"

namespace mvr {

// Spans: the CPU's exact spans (Cpu) filled by GPU compute shaders.
enum class PstMode { Quad, Strip, Exact, Cpu, Spans };
inline constexpr NameTable<PstMode, 5> kPstModeNames{{{PstMode::Quad, "quad"},
                                                      {PstMode::Strip, "strip"},
                                                      {PstMode::Exact, "exact"},
                                                      {PstMode::Cpu, "cpu"},
                                                      {PstMode::Spans, "spans"}}};

inline PstMode parsePstMode(const std::string& name) {  // throws on unknown
  return parseName(kPstModeNames, name, "--pst", "mode");
}
inline const char* pstModeName(PstMode mode) { return nameOf(kPstModeNames, mode); }

// How the texture pass samples: Halle's 1-D texture vectors (default), or
// the 2D texture directly with a per-pixel divide (for comparison).
enum class TextureMode { Vector, Direct };
inline constexpr NameTable<TextureMode, 2> kTextureModeNames{
    {{TextureMode::Vector, "vector"}, {TextureMode::Direct, "direct"}}};
inline TextureMode parseTextureMode(const std::string& name) {  // throws on unknown
  return parseName(kTextureModeNames, name, "--texture", "mode");
}

// Where the GL modes slice and build PST geometry: on the GPU (slice table
// and PSTs in GPU memory), or on the CPU with PSTs uploaded per batch (the
// reference the GPU path is tested against; the texture-vector passes
// always use it). Auto, the default: the GPU, unless GL itself renders on
// the CPU (llvmpipe), where the CPU path's lower per-view cost wins
// (docs/BENCHMARKS.md, issue 14).
enum class PstBuilder { Auto, Gpu, Cpu };
inline constexpr NameTable<PstBuilder, 3> kPstBuilderNames{
    {{PstBuilder::Auto, "auto"}, {PstBuilder::Gpu, "gpu"}, {PstBuilder::Cpu, "cpu"}}};

// What the rasterizers shade with beyond the lit colours: the scene's
// lights, materials and textures and the plan's passes. No scene: diffuse
// only.
struct EpiShading {
  const Scene* scene = nullptr;
  shading::ShadingPlan plan;
  const shading::TextureSet* textures = nullptr;  // when plan.texture
  const shading::EnvironmentSet* environment = nullptr;  // when plan.reflection
  TextureMode textureMode = TextureMode::Vector;
  // Image-based slices: every slice is coloured by its own texture vector
  // (ExtremeVertices::vectors) in one pass, with no scene and no lighting.
  bool sliceVectors = false;
  // With sliceVectors: add each slice's split-track highlight
  // (SliceVector's knots), linear in the view between knots.
  bool sliceHighlights = false;
};

class EpiRasterizer {
 public:
  virtual ~EpiRasterizer() = default;
  // Fills the EPIs of every scanline of one row of views and hands each to
  // the sink as sink.putEpi(row, scanline, W x N image). The table may live
  // in host or GPU memory; each rasterizer reads the form it needs.
  virtual void rasterize(const ExtremeVertices& vertices, const SliceTableView& table,
                         const ShearingCamera& camera, int row, FrameSink& sink,
                         RenderStats& stats) = 0;
  // The same from vertices and a table a GPU pass wrote (the image-based
  // back end's GPU slicer); only for a rasterizer that readsDeviceTable(),
  // others throw mvr::Error.
  virtual void rasterize(const GpuVertices& vertices, const GpuSliceTable& table,
                         const ShearingCamera& camera, int row, FrameSink& sink, RenderStats& stats);
  // Whether it reads the table from GPU buffers (then a GPU slicer saves
  // the upload) rather than from host memory.
  virtual bool readsDeviceTable() const { return false; }
};

// The one place that chooses between CPU and GL: the span rasterizer for
// PstMode::Cpu, the GPU span rasterizer for PstMode::Spans, else the GL
// rasterizer in that mode (needs a current GL context).
std::unique_ptr<EpiRasterizer> makeRasterizer(PstMode mode, PixelType type,
                                              const EpiShading& shading = {},
                                              PstBuilder builder = PstBuilder::Auto);

// How the span rasterizer walks a PST and fills untextured diffuse slices.
// Every choice fills the same pixels with the same bytes; the defaults are
// the fastest, and tests force the others to compare them.
struct SpanPaths {
  enum class Walk { Auto, Rows, Columns } walk = Walk::Auto;
  bool fastDiffuse = true;  // four pixels at a time, and one encoding for a slice whose pixels share it
  bool baselineIsa = false;  // x86-64's baseline code even where the CPU has x86-64-v2
};

// Exact spans on every core of the thread pool (mvr/parallel.h).
std::unique_ptr<EpiRasterizer> makeSpanRasterizer(PixelType type, const EpiShading& shading = {},
                                                  SpanPaths paths = {});
// The CPU's spans by compute shaders (epi/gpu/gpu_span_rasterizer.cpp);
// diffuse shading only; needs a current GL context.
std::unique_ptr<EpiRasterizer> makeGpuSpanRasterizer(PixelType type, const EpiShading& shading = {});
// The most bytes of EPIs one of its dispatches fills (default 64 MB),
// process-wide: tests make sets of a few EPIs take several batches.
void setGpuSpanBatchBytes(size_t bytes);
// Quad, strip or exact; needs a current GL context.
std::unique_ptr<EpiRasterizer> makeGlRasterizer(PstMode mode, PixelType type,
                                                const EpiShading& shading = {},
                                                PstBuilder builder = PstBuilder::Auto);

}  // namespace mvr
