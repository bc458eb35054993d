#include "epi/interp_renderer.h"

#include <cmath>

#include "mvr/error.h"
#include "mvr/source_layers.h"
#include "slicing/image_slices.h"

namespace mvr {

Acquire parseAcquire(const std::string& name) {
  if (name == "center") return Acquire::Center;
  if (name == "dual") return Acquire::Dual;
  fail("--acquire", "unknown acquisition '" + name + "' (expected center or dual)");
}

const char* acquireName(Acquire acquire) { return acquire == Acquire::Center ? "center" : "dual"; }

namespace {

// Every image slice is coloured by its own vector of source pixels.
const EpiShading kVectors{.sliceVectors = true};

class InterpRenderer final : public Renderer {
 public:
  InterpRenderer(const Scene& scene, PixelType type, const InterpOptions& options)
      : options_(options), sources_(makeSourceLayerRenderer(scene)),
        rasterizer_(options.mode == PstMode::Cpu ? makeSpanRasterizer(type, 2, kVectors)
                                                 : makeGlRasterizer(options.mode, type, kVectors)) {
    if (options.maxLayers < 1) fail("--max-layers", "must be at least 1");
    if (!(options.coalesce >= 0.0f) || !std::isfinite(options.coalesce))
      fail("--coalesce", "must be a finite number of pixels, at least 0");
  }

  std::string name() const override { return "interp"; }
  FrameOrder order() const override { return FrameOrder::Epi; }

  void render(const ShearingCamera& cam, FrameSink& sink, RenderStats& stats) override {
    const double trackWidth = std::abs(cam.spec().trackRight - cam.spec().trackLeft);
    for (int row = 0; row < cam.rows(); ++row) {
      std::vector<SourceLayer> layers;
      for (double x : sourceEyes(cam)) {
        std::vector<SourceLayer> more =
            sources_->render(cam, {x, cam.rowY(row)}, options_.maxLayers, trackWidth, stats);
        stats.counters["source_views"] += 1;
        for (SourceLayer& l : more) layers.push_back(std::move(l));
      }
      stats.counters["layers"] += double(layers.size());
      ImageSlices slices;
      {
        ScopedStage s(stats.times, "slicing");
        slices = sliceSourceLayers(layers, cam, row, {options_.overlap, options_.coalesce});
      }
      stats.counters["slices"] += double(slices.table.sliceCount());
      stats.counters["slice_pixels"] += double(slices.pixels);
      stats.counters["slice_table_bytes"] =
          std::max(stats.counters["slice_table_bytes"], double(slices.table.bytes()));
      rasterizer_->rasterize(slices.vertices, slices.table, cam, row, sink, stats);
    }
    stats.notes["acquire"] = acquireName(options_.acquire);
    stats.notes["pst"] = pstModeName(options_.mode);
    stats.counters["max_layers"] = options_.maxLayers;
    stats.counters["coalesce"] = options_.coalesce;
  }

 private:
  std::vector<double> sourceEyes(const ShearingCamera& cam) const {
    const double left = cam.viewX(0), right = cam.viewX(cam.views() - 1);
    if (options_.acquire == Acquire::Center || cam.views() == 1) return {0.5 * (left + right)};
    return {left, right};
  }

  InterpOptions options_;
  std::unique_ptr<SourceLayerRenderer> sources_;
  std::unique_ptr<EpiRasterizer> rasterizer_;
};

}  // namespace

std::unique_ptr<Renderer> makeInterpRenderer(const Scene& scene, PixelType type,
                                             const InterpOptions& options) {
  return std::make_unique<InterpRenderer>(scene, type, options);
}

}  // namespace mvr
