#include "mvr/backends/warp/warp_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "epi/epi_batch.h"
#include "mvr/backends/warp/depth_warp.h"
#include "mvr/backends/warp/warp_spans.h"
#include "mvr/error.h"
#include "mvr/gl/gl_api.h"
#include "mvr/views/source_layers.h"
#include "mvr/views/track_refinement.h"
#include "mvr/views/view_loop.h"

namespace mvr {

namespace {

struct Reference {
  WarpReference gpu;
  double x = 0.0;  // camera x on the track (scene sources)
};

// Camera z from a reversed-Z window depth (ShearingCamera::unprojectAt).
float cameraDepth(const CameraSpec& s, float window) {
  const double n = s.nearDistance, f = s.farDistance;
  return window > 0.0f ? float(n * f / (double(window) * (f - n) + n)) : 0.0f;
}

class WarpRenderer final : public Renderer {
 public:
  // track: the views a capture will be rendered as, if known (the CPU
  // warp needs its references on their rows).
  WarpRenderer(const Scene* scene, std::vector<RgbdView> captured, PixelType type, const WarpOptions& options,
               const ShearingCamera* track)
      : options_(resolved(options, scene || onRows(captured, track))),
        type_(type),
        warp_(options_.path == WarpPath::Cpu ? nullptr : std::make_unique<DepthWarp>(options.tau, options.penalty)),
        sources_(scene ? makeSourceLayerRenderer(*scene, false,
                                                 options_.path == WarpPath::Cpu ? options_.outlineSamples : 1)
                       : nullptr) {
    if (!scene && captured.empty()) fail("warp", "no references");
    if (options_.path == WarpPath::Cpu) {
      for (RgbdView& view : captured) capturedViews_.push_back(std::make_shared<const RgbdView>(std::move(view)));
      return;
    }
    // A captured reference serves the views between it and the others.
    for (const RgbdView& view : captured) {
      double baseline = 0.0;
      for (const RgbdView& other : captured)
        baseline = std::max(baseline, glm::length(other.center() - view.center()));
      captured_.push_back({WarpReference::upload(view, options_.tau, options_.flatness, baseline)});
    }
  }

  std::string name() const override { return "warp"; }
  FrameOrder order() const override { return options_.path == WarpPath::Cpu ? FrameOrder::Epi : FrameOrder::View; }

  void render(const ShearingCamera& cam, FrameSink& sink, RenderStats& stats) override {
    if (options_.path == WarpPath::Cpu) return renderEpis(cam, sink, stats);
    RenderTarget target(cam.width(), cam.height(), type_);
    int loadedRow = -1;
    std::vector<Reference> rowSources;
    renderEachView(cam, target, sink, stats, [&](int row, int view) {
      if (sources_ && row != loadedRow) {
        ScopedStage s(stats.times, "sources");
        rowSources = acquire(cam, row, stats);
        loadedRow = row;
      }
      const std::vector<Reference>& refs = sources_ ? rowSources : captured_;
      const glm::dvec3 eye = cam.eye(view, row);
      std::vector<glm::dvec3> centres;
      for (const Reference& r : refs) centres.emplace_back(r.gpu.center);
      const auto [a, b] = nearestPair(centres, eye);
      ScopedStage s(stats.times, "warp");
      warp_->render(refs[a].gpu, b < 0 ? nullptr : &refs[b].gpu, cameraOf(cam, view, row), target);
    });
    stats.notes["acquire"] = sources_ ? acquireName(options_.acquire) : "captured";
    stats.notes["warp"] = "gl";
  }

 private:
  // Auto made Cpu or Gl (WarpOptions::path); validated. cpuFits: the CPU
  // warp can take the references (scene sources, or a capture on the
  // track's rows).
  static WarpOptions resolved(WarpOptions o, bool cpuFits) {
    validate(o);
    if (o.path == WarpPath::Auto) o.path = cpuFits && gl::rendersOnCpu() ? WarpPath::Cpu : WarpPath::Gl;
    if (o.path == WarpPath::Cpu && !cpuFits)
      fail("--warp-path", "cpu needs references on the rows of the views' track: the same camera, size and rows");
    return o;
  }

  // The references on row `row` of cam: each the view of cam's camera at
  // its eye, on that row (K and V as cam's there), of cam's size.
  static std::vector<int> onRow(const std::vector<const RgbdView*>& refs, const ShearingCamera& cam, int row) {
    auto same = [](const auto& a, const auto& b, int n) {
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          if (!(std::abs(a[i][j] - b[i][j]) <= 1e-6 * (1.0 + std::abs(b[i][j])))) return false;
      return true;
    };
    std::vector<int> out;
    for (int k = 0; k < int(refs.size()); ++k) {
      const RgbdView& r = *refs[size_t(k)];
      const double x = r.center().x, y = cam.rowY(row);
      if (r.color.width == cam.width() && r.color.height == cam.height() && same(r.V, cam.worldToCameraAt(x, y), 4) &&
          same(r.K, cam.intrinsicsAt(x, y), 3))
        out.push_back(k);
    }
    return out;
  }

  // Whether every row of track has a reference on it.
  static bool onRows(const std::vector<RgbdView>& refs, const ShearingCamera* track) {
    if (!track || refs.empty()) return false;
    std::vector<const RgbdView*> pointers;
    for (const RgbdView& r : refs) pointers.push_back(&r);
    for (int row = 0; row < track->rows(); ++row)
      if (onRow(pointers, *track, row).empty()) return false;
    return true;
  }

  static WarpCamera cameraOf(const ShearingCamera& cam, int view, int row) {
    return {cam.viewProjection(view, row),
            RgbdView::pixelToWorld(cam.intrinsics(view, row), cam.worldToCamera(view, row)), cam.eye(view, row)};
  }

  std::vector<Reference> acquire(const ShearingCamera& cam, int row, RenderStats& stats) {
    const int n = cam.views();
    std::vector<Reference> refs;
    refs.push_back(source(cam, row, cam.viewX(0), stats));
    if (n > 1) refs.push_back(source(cam, row, cam.viewX(n - 1), stats));
    if (options_.acquire == Acquire::Hierarchical && n > 2)
      refine(
          cam,
          [&](int a, int b, int m) {
            return warp_->holes(refs[size_t(a)].gpu, refs[size_t(b)].gpu, cameraOf(cam, m, row), cam.width(),
                                cam.height());
          },
          [&](int m) { refs.push_back(source(cam, row, cam.viewX(m), stats)); }, stats);
    return refs;
  }

  // The CPU's EPIs: each row's sources, then its scanlines on the pool.
  void renderEpis(const ShearingCamera& cam, FrameSink& sink, RenderStats& stats) {
    const RenderShare& share = cam.share();
    // A share's scanlines need the sources' rows beside them too: the
    // labels and silhouettes look one pixel up and down. Hierarchical
    // acquisition counts holes over the whole view, so that every share
    // of a split job picks the same sources.
    RenderShare around = share;
    around.scanlines = options_.acquire == Acquire::Hierarchical
                           ? IndexRange{0, cam.height()}
                           : IndexRange{std::max(0, share.scanlines.begin - 1),
                                        std::min(cam.height(), share.scanlines.end + 1)};
    const ShearingCamera sourceCam = cam.withShare(around);
    std::vector<const RgbdView*> captured;
    for (const auto& view : capturedViews_) captured.push_back(view.get());
    for (int row = share.rows.begin; row < share.rows.end; ++row) {
      WarpSpans spans(cam, row, type_, options_.tau, options_.penalty);
      if (!sources_) {
        const std::vector<int> mine = onRow(captured, cam, row);
        if (mine.empty()) fail("warp", "row " + std::to_string(row) + " of the views has no reference on it");
        for (int k : mine) spans.add(capturedViews_[size_t(k)], captured[size_t(k)]->center().x);
      } else {
        ScopedStage s(stats.times, "sources");
        auto add = [&](int view) {
          spans.add(sourceView(sourceCam, row, cam.viewX(view), stats), cam.viewX(view));
        };
        add(0);
        if (cam.views() > 1) add(cam.views() - 1);
        if (options_.acquire == Acquire::Hierarchical && cam.views() > 2)
          refine(cam, [&](int a, int b, int m) { return spans.holes(a, b, m); }, add, stats);
      }
      ScopedStage s(stats.times, "warp");
      fillEpisInOrder(sink, row, share.scanlines, cam.width(), cam.views(), type_, ring_,
                      [&](int j, const PixelRows& epi) { spans.fillEpi(j, epi); });
    }
    stats.notes["acquire"] = sources_ ? acquireName(options_.acquire) : "captured";
    stats.notes["warp"] = "cpu";
  }

  // refineTrack (mvr/views/track_refinement.h) with this back end's budget and
  // tolerance, the sources appended in the order their views come:
  // holes(a, b, view) counts the holes sources a and b (indices) leave in
  // a view, add(view) appends a source there.
  template <class Holes, class Add>
  void refine(const ShearingCamera& cam, Holes&& holes, Add&& add, RenderStats& stats) {
    std::vector<int> viewOf{0, cam.views() - 1};  // each source's view
    auto source = [&](int view) { return int(std::find(viewOf.begin(), viewOf.end(), view) - viewOf.begin()); };
    refineTrack(
        cam, options_.holeFraction, options_.budget, int(viewOf.size()), stats,
        [&](int a, int b, int m) { return holes(source(a), source(b), m); },
        [&](int m) {
          add(m);
          viewOf.push_back(m);
        });
  }

  // One source view: the deferred pipeline's nearest layer as an RGB-D image.
  RgbdView sourceView(const ShearingCamera& cam, int row, double x, RenderStats& stats) {
    stats.counters["source_views"] += 1;
    const double y = cam.rowY(row);
    std::vector<SourceLayer> layers = sources_->render(cam, {x, y}, 1, 0.0, stats);
    RgbdView view;
    view.K = cam.intrinsicsAt(x, y);
    view.V = cam.worldToCameraAt(x, y);
    view.depth = DepthImage(cam.width(), cam.height());
    if (layers.empty()) {
      view.color = Image(cam.width(), cam.height(), PixelType::F32);
    } else {
      view.color = std::move(layers[0].color);
      for (size_t k = 0; k < view.depth.values.size(); ++k)
        view.depth.values[k] = cameraDepth(cam.spec(), layers[0].depth[k]);
      const std::vector<PixelOutline>& outline = layers[0].outline;
      if (!outline.empty()) view.ends.resize(outline.size());
      for (size_t k = 0; k < outline.size(); ++k)
        if (const PixelOutline& o = outline[k]; o.right >= 0.0f)
          view.ends[k] = {o.left, cameraDepth(cam.spec(), o.leftDepth), o.right, cameraDepth(cam.spec(), o.rightDepth)};
    }
    return view;
  }

  // A source uploaded for the GL warp.
  Reference source(const ShearingCamera& cam, int row, double x, RenderStats& stats) {
    const RgbdView view = sourceView(cam, row, x, stats);
    const double y = cam.rowY(row);
    // Both references of a view are warped to it: any view may be drawn
    // from a source, as far as the track's far corners.
    double baseline = 0.0;
    for (int v : {0, cam.views() - 1})
      for (int r : {0, cam.rows() - 1})
        baseline = std::max(baseline, glm::length(glm::dvec2(cam.viewX(v) - x, cam.rowY(r) - y)));
    Reference r{WarpReference::upload(view, options_.tau, options_.flatness, baseline), x};
    // What every view draws of it: a CPU GL pays per triangle.
    stats.counters["reference_triangles"] += double((r.gpu.triangleIndexCount + r.gpu.splatIndexCount) / 3);
    return r;
  }

  WarpOptions options_;
  PixelType type_;
  std::unique_ptr<DepthWarp> warp_;  // the GL warp, or null (cpu)
  std::unique_ptr<SourceLayerRenderer> sources_;  // scene sources, or null
  std::vector<Reference> captured_;                          // uploaded for the GL warp
  std::vector<std::shared_ptr<const RgbdView>> capturedViews_;  // or kept for the CPU's
  std::vector<Image> ring_;  // the CPU's EPIs being filled and handed on (fillEpisInOrder)
};

}  // namespace

std::unique_ptr<Renderer> makeWarpRenderer(const Scene& scene, PixelType type, const WarpOptions& options) {
  return std::make_unique<WarpRenderer>(&scene, std::vector<RgbdView>{}, type, options, nullptr);
}

std::unique_ptr<Renderer> makeWarpRenderer(std::vector<RgbdView> references, PixelType type,
                                           const WarpOptions& options, const ShearingCamera* track) {
  return std::make_unique<WarpRenderer>(nullptr, std::move(references), type, options, track);
}

}  // namespace mvr
