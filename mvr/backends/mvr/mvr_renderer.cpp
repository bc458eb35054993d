#include "mvr/backends/mvr/mvr_renderer.h"

#include <algorithm>
#include <optional>

#include "mvr/gl/gpu_clock.h"
#include "shading/lighting.h"
#include "slicing/extreme_vertices.h"
#include "slicing/gpu/gpu_slicer.h"
#include "slicing/gpu/gpu_transform.h"
#include "slicing/slice_table.h"

namespace mvr {
namespace {

class MvrRenderer final : public Renderer {
 public:
  MvrRenderer(const Scene& scene, PstMode mode, PixelType type, TextureMode texture,
              PstBuilder builder)
      : scene_(scene), mode_(mode),
        textures_(shading::TextureSet::load(scene)),
        environment_(shading::EnvironmentSet::load(scene)),
        shading_{&scene, shading::planShading(scene), &textures_, &environment_, texture},
        rasterizer_(makeRasterizer(mode, type, shading_, builder)), bounds_(scene.bounds()) {}

  std::string name() const override { return "mvr"; }

  // Per frame of a sequence only the lighting, the extreme-vertex transform
  // and the slicing are redone; textures, shaders and the rasterizer stay,
  // and the GPU transform's buffers, written again.
  bool sceneMoved() override {
    lit_.reset();
    gpuMoved_ = true;
    bounds_ = scene_.bounds();
    return true;
  }
  FrameOrder order() const override { return FrameOrder::Epi; }

  void render(const ShearingCamera& cam, FrameSink& sink, RenderStats& stats) override {
    const bool resident =
        rasterizer_->readsDeviceTable() && GpuExtremeTransform::needsNoClipping(bounds_, cam);
    if (resident)
      renderOnGpu(cam, sink, stats);
    else
      renderFromHost(cam, sink, stats);
    stats.notes["transform"] = resident ? "gpu" : "cpu";
    stats.notes["pst"] = pstModeName(mode_);
    stats.notes["passes"] = shading_.plan.passNames();
    if (shading_.plan.texture)
      stats.notes["texture"] = mode_ == PstMode::Cpu || shading_.textureMode == TextureMode::Direct
                                   ? "direct" : "vector";
    stats.counters["passes"] = double(shading_.plan.passes().size());
  }

 private:
  // Transform, slicing and PSTs on the GPU: the scene is uploaded (and lit,
  // view independently) once; per row of views, compute passes and draws.
  void renderOnGpu(const ShearingCamera& cam, FrameSink& sink, RenderStats& stats) {
    if (!gpuTransform_ || gpuMoved_) {
      shading::VertexColors colors;
      std::vector<float> extras;
      {
        ScopedStage s(stats.times, "lighting");
        colors = shading::litVertexColors(scene_);
        extras = shading::vertexExtras(scene_, shading_.plan);
      }
      ScopedStage s(stats.times, "upload");
      if (gpuTransform_)
        gpuTransform_->moved(scene_, colors, extras);
      else
        gpuTransform_.emplace(scene_, colors, extras, shading_.plan.extraCount);
      gpuMoved_ = false;
    }
    if (!gpuSlicer_) gpuSlicer_.emplace();
    stats.counters["clipped_triangles"] = double(scene_.triangleCount());
    for (int row = cam.share().rows.begin; row < cam.share().rows.end; ++row) {
      const GpuVertices* vertices = nullptr;
      {
        ScopedStage s(stats.times, "transform");
        gl::GpuClock::mark("transform");
        vertices = &gpuTransform_->transform(cam, row);
      }
      std::optional<GpuSliceTable> table;
      {
        ScopedStage s(stats.times, "slicing");
        gl::GpuClock::mark("slicing");
        table.emplace(gpuSlicer_->build(gpuTransform_->yBuffer(), vertices->triangles.id(),
                                        uint32_t(vertices->triangleCount), cam.height(),
                                        cam.share().scanlines));
      }
      countSlices(table->sliceCount(), stats);
      rasterizer_->rasterize(*vertices, *table, cam, row, sink, stats);
    }
  }

  void renderFromHost(const ShearingCamera& cam, FrameSink& sink, RenderStats& stats) {
    if (!lit_) {
      // Diffuse lighting is view independent: once per renderer (Halle
      // 5.6.2), however many sequences or shares it renders.
      ScopedStage s(stats.times, "lighting");
      lit_.emplace(Lit{shading::litVertexColors(scene_), shading::vertexExtras(scene_, shading_.plan),
                       TriangleRuns::of(scene_)});
    }
    ExtremeVertices vertices;
    {
      // A share of the scanlines transforms only the triangles that reach it.
      ScopedStage s(stats.times, "transform");
      vertices = transformToExtremes(scene_, lit_->colors, cam, 0, lit_->extras, shading_.plan.extraCount, &lit_->runs);
    }
    stats.counters["extreme_vertex_bytes"] = double(vertices.bytes());
    stats.counters["clipped_triangles"] = double(vertices.triangles.size());
    for (int row = cam.share().rows.begin; row < cam.share().rows.end; ++row) {
      if (row > 0) {
        // Halle 5.6.11: the next row needs one multiply-add per vertex.
        ScopedStage s(stats.times, "row_step");
        moveToRow(vertices, row);
      }
      if (rasterizer_->readsDeviceTable()) {
        // Sliced on the GPU: only the offsets come back to the host.
        if (!gpuSlicer_) gpuSlicer_.emplace();
        std::optional<GpuSliceTable> table;
        {
          ScopedStage s(stats.times, "slicing");
          table.emplace(gpuSlicer_->build(vertices, cam.height(), cam.share().scanlines));
        }
        countSlices(table->sliceCount(), stats);
        rasterizer_->rasterize(vertices, *table, cam, row, sink, stats);
        continue;
      }
      SliceTable table;
      {
        ScopedStage s(stats.times, "slicing");
        table = SliceTable::build(vertices, cam.height(), cam.share().scanlines);
      }
      countSlices(table.sliceCount(), stats);
      rasterizer_->rasterize(vertices, table, cam, row, sink, stats);
    }
  }

  static void countSlices(size_t slices, RenderStats& stats) {
    stats.counters["slices"] += double(slices);
    stats.counters["slice_table_bytes"] =
        std::max(stats.counters["slice_table_bytes"], double(slices * sizeof(Slice)));
  }

  const Scene& scene_;
  PstMode mode_;
  shading::TextureSet textures_;
  shading::EnvironmentSet environment_;
  EpiShading shading_;
  std::unique_ptr<EpiRasterizer> rasterizer_;
  Bounds bounds_;
  std::optional<GpuSlicer> gpuSlicer_;  // when the rasterizer reads GPU tables
  std::optional<GpuExtremeTransform> gpuTransform_;  // when, besides, nothing needs clipping
  bool gpuMoved_ = false;  // the scene moved since gpuTransform_ took it
  struct Lit {
    shading::VertexColors colors;
    std::vector<float> extras;
    TriangleRuns runs;
  };
  std::optional<Lit> lit_;  // the host path's view-independent vertex data
};

}  // namespace

std::unique_ptr<Renderer> makeMvrRenderer(const Scene& scene, PstMode mode, PixelType type,
                                          TextureMode texture, PstBuilder builder) {
  return std::make_unique<MvrRenderer>(scene, mode, type, texture, builder);
}

}  // namespace mvr
