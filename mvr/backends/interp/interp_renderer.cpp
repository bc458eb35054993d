#include "mvr/backends/interp/interp_renderer.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "mvr/backends/interp/source_views.h"
#include "mvr/error.h"
#include "mvr/gl/gl_api.h"
#include "mvr/gl/gpu_clock.h"
#include "mvr/parallel.h"
#include "mvr/views/source_layers.h"
#include "mvr/views/track_refinement.h"
#include "shading/shading_plan.h"
#include "slicing/gpu/gpu_image_slicer.h"
#include "slicing/gpu/gpu_source_visibility.h"
#include "slicing/image_slices.h"
#include "slicing/source_visibility.h"

namespace mvr {

namespace {

const InterpOptions& validated(const InterpOptions& options) {
  validate(options);
  return options;
}

// Split tracks only where some material has a highlight to split.
int splitsFor(const Scene& scene, const InterpOptions& options) {
  return shading::planShading(scene).specular ? options.splits : 0;
}

class InterpRenderer final : public Renderer {
 public:
  InterpRenderer(const Scene& scene, PixelType type, const InterpOptions& options)
      : options_(validated(options)), type_(type), scene_(scene), splits_(splitsFor(scene, options)),
        sources_(makeSourceLayerRenderer(scene, splits_ > 0, options_.outlineSamples,
                                         options_.onePass ? Peeling::OnePass : Peeling::PassPerLayer)) {
    // Every image slice is coloured by its own vector of source pixels.
    const EpiShading shading{.sliceVectors = true, .sliceHighlights = splits_ > 0};
    rasterizer_ = makeRasterizer(options.mode, type, shading, options.builder);
    // Layers stay on the GPU when nothing needs their pixels on the host:
    // no split highlights or blending. Visibility and hole counts have
    // compute passes, run where a GPU runs them (or by name): on llvmpipe
    // the host's are faster (teacup 320x240 x 100, hierarchical:2:c1:spans:
    // 0.33 s against 0.40).
    const bool judged = options_.visibility || options_.acquire == Acquire::Hierarchical;
    const bool judgeOnGpu = options_.builder == PstBuilder::Gpu ||
                            (options_.builder == PstBuilder::Auto && !gl::rendersOnCpu());
    if (rasterizer_->readsDeviceTable() && splits_ == 0 && options_.blend == Blend::None && (!judged || judgeOnGpu)) {
      gpuSlicer_.emplace();
      if (judged) gpuVisibility_.emplace();
    }
  }

  std::string name() const override { return "interp"; }
  FrameOrder order() const override { return FrameOrder::Epi; }

  void render(const ShearingCamera& cam, FrameSink& sink, RenderStats& stats) override {
    for (int row = cam.share().rows.begin; row < cam.share().rows.end; ++row) {
      if (gpuSlicer_) {
        renderOnGpu(cam, row, sink, stats);
        continue;
      }
      std::vector<Source> sources = acquire(cam, row, stats);
      std::sort(sources.begin(), sources.end(), [](const Source& a, const Source& b) { return a.x < b.x; });
      for (const Source& source : sources) stats.counters["layers"] += double(source.layers.size());
      const std::vector<SourceView> views = sourceViews(cam, sources, passesThrough());
      SourceViewSink out(sink, views);
      if (sources.size() == 1) renderWhole(cam, row, sources, out, stats);
      else renderIntervals(cam, row, sources, out, stats);
    }
    stats.notes["acquire"] = acquireName(options_.acquire);
    stats.notes["image_slicer"] = gpuSlicer_ ? "gpu" : "cpu";
    stats.notes["pst"] = pstModeName(options_.mode);
    stats.notes["blend"] = nameOf(kBlendNames, options_.blend);
    stats.counters["max_layers"] = options_.maxLayers;
    stats.counters["coalesce"] = options_.coalesce;
    stats.counters["visibility"] = options_.visibility;
    stats.counters["splits"] = splits_;
    stats.counters["outline_samples"] = options_.outlineSamples;
  }

 private:
  // Every source's slices over the whole track, depth-tested together.
  void renderWhole(const ShearingCamera& cam, int row, std::vector<Source>& sources, FrameSink& out,
                   RenderStats& stats) {
    std::vector<SourceLayer> layers;
    for (Source& source : sources)
      for (SourceLayer& l : source.layers) layers.push_back(std::move(l));
    const ImageSlices slices = slice(layers, cam, row, stats);
    rasterizer_->rasterize(slices.vertices, slices.table, cam, row, out, stats);
  }

  // The views between each two neighbouring sources from those two alone,
  // as de Quilletes interpolates: a source's slices, exact at its eye, are
  // extrapolated no farther than its neighbours (across the whole track,
  // the far sources' slices of a curved surface stand out of the outline
  // between two near ones: 9 sources on the bunny scored 18.6 dB against
  // dual's 26.5; issue 18). And each half of an interval from its near
  // source's layers and the far source's nearest layer alone: the far
  // source's deeper layers, chords of surfaces it saw behind others,
  // extrapolated past the middle won depth tests they should lose (the
  // teacup at 640x480 x 100, dual: 35.3 -> 40.2 dB). Each piece is
  // rendered through a camera of its own views, in bands of scanlines that
  // bound the EPIs held.
  void renderIntervals(const ShearingCamera& cam, int row, const std::vector<Source>& sources, FrameSink& out,
                       RenderStats& stats) {
    std::vector<Piece> pieces;
    for (size_t k = 0; k + 1 < sources.size(); ++k) {
      const int a = viewAt(cam, sources[k].x), b = viewAt(cam, sources[k + 1].x);
      if (a < 0 || b <= a) fail("interp", "a source's eye is not a view of the set");
      const int layersA = int(sources[k].layers.size()), layersB = int(sources[k + 1].layers.size());
      for (const PieceLayers& p : pieceLayers(a, b, layersA, layersB, halves())) {
        std::vector<SourceLayer> layers;
        for (int i = 0; i < p.fromA; ++i) layers.push_back(sources[k].layers[size_t(i)]);
        for (int i = 0; i < p.fromB; ++i) layers.push_back(sources[k + 1].layers[size_t(i)]);
        pieces.push_back({p.first, p.last, a, b,
                          slice(layers, intervalCamera(cam, p.first, p.last, cam.share().scanlines), row, stats),
                          uint32_t(p.fromA)});
      }
    }
    // assemble draws over the last band's EPIs: every view must be drawn.
    if (pieces.front().first != 0 || pieces.back().last != cam.views() - 1)
      fail("interp", "the source views do not reach both ends of the track");
    assemble(cam, row, int(pieces.size()), out, [&](int k, IndexRange scanlines, std::vector<Image>& into) {
      drawPiece(pieces[size_t(k)], cam, scanlines, row, into, stats);
    });
  }

  // The views [first, last] of a piece of the interval between sources at
  // views a and b, and how many layers of each (front first) it draws.
  struct PieceLayers {
    int first, last, fromA, fromB;
  };
  // Halves of one length (a rasterizer keeps its targets between calls
  // of one size), sharing the middle view where the count is odd, which
  // the second draws; an interval too short to halve is drawn whole, and
  // so is one whose sources are blended (blending weighs what each source
  // alone draws over the whole interval: halved, the bunny's blended views
  // lost 0.4-0.9 dB).
  static std::vector<PieceLayers> pieceLayers(int a, int b, int layersA, int layersB, bool halve) {
    if (!halve || b - a < 2 || layersA == 0 || layersB == 0) return {{a, b, layersA, layersB}};
    const int length = (b - a) / 2 + 1;
    return {{a, a + length - 1, layersA, 1}, {b - length + 1, b, 1, layersB}};
  }

  // Hands on the EPIs of cam's share, each assembled from `count` pieces
  // drawn a band of scanlines at a time (draw(k, scanlines, into): piece
  // k's EPIs of those scanlines written into their views' rows of `into`);
  // later pieces overwrite the views they share with earlier ones. The
  // pieces together draw every view, so a band's EPIs are the last band's
  // images drawn over (fresh ones cost page faults and zero fill: 5% of
  // interp dual's time on the CPU spans).
  template <class Draw>
  void assemble(const ShearingCamera& cam, int row, int count, FrameSink& out, Draw&& draw) {
    const IndexRange lines = cam.share().scanlines;
    const int band = bandScanlines(cam, count > 1);
    std::vector<Image>& epis = assembled_;
    for (int first = lines.begin; first < lines.end; first += band) {
      const IndexRange part{first, std::min(lines.end, first + band)};
      epis.resize(size_t(part.size()));
      for (int k = 0; k < count; ++k) draw(k, part, epis);
      for (int s = 0; s < part.size(); ++s) out.putEpiInPlace(row, part.begin + s, epis[size_t(s)]);
    }
  }

  // A piece's EPIs in the rows of its views in the EPIs of all views: the
  // rasterizer fills them there (epiMemory), or they are copied in as
  // they come; no EPI of the piece's own is kept.
  class IntoViews final : public FrameSink {
   public:
    IntoViews(std::vector<Image>& epis, int firstScanline, int firstView, int views)
        : epis_(epis), firstScanline_(firstScanline), firstView_(firstView), views_(views) {}
    void putEpi(int, int scanline, const Image& epi) override {
      std::copy_n(epi.bytes.data(), epi.bytes.size(), rowsFor(scanline, epi.width, epi.height, epi.type));
    }
    uint8_t* epiMemory(int, int scanline, int width, int views, PixelType type) override {
      return rowsFor(scanline, width, views, type);
    }

   private:
    uint8_t* rowsFor(int scanline, int width, int views, PixelType type) {
      if (firstView_ + views > views_) fail("interp", "a piece's views run past the set's");
      Image& e = epis_[size_t(scanline - firstScanline_)];
      if (e.width != width || e.height != views_ || e.type != type) e = Image(width, views_, type);
      return e.row(firstView_);
    }

    std::vector<Image>& epis_;
    int firstScanline_, firstView_, views_;
  };

  // A run of views drawn from one set of slices: a piece of the interval
  // between two neighbouring sources (at views a and b).
  struct Piece {
    int first, last;    // its views
    int a, b;           // the two sources' views
    ImageSlices slices;
    uint32_t firstOfB;  // the first layer of the second source
  };

  // One piece's EPIs of the given scanlines, written into its views' rows
  // of `into`: the depth-tested joint EPIs, blended with each source's own
  // where blending is on (weights over the whole interval).
  void drawPiece(const Piece& p, const ShearingCamera& cam, IndexRange scanlines, int row, std::vector<Image>& into,
                 RenderStats& stats) {
    const ShearingCamera sub = intervalCamera(cam, p.first, p.last, scanlines);
    IntoViews sink(into, scanlines.begin, p.first, cam.views());
    if (options_.blend == Blend::None)
      return rasterizer_->rasterize(p.slices.vertices, p.slices.table, sub, row, sink, stats);
    std::vector<Image> joint = draw(p.slices, p.slices.table, sub, row, stats);
    const auto ofB = [&](uint32_t t) { return p.slices.layerOf[t] >= p.firstOfB; };
    const std::vector<Image> a = draw(p.slices, p.slices.table.keeping([&](uint32_t t) { return !ofB(t); }), sub,
                                      row, stats);
    const std::vector<Image> b = draw(p.slices, p.slices.table.keeping(ofB), sub, row, stats);
    const ShearingCamera interval = intervalCamera(cam, p.a, p.b, scanlines);
    ScopedStage s(stats.times, "blend");
    parallelFor(0, scanlines.size(), [&](int k) {
      blendEpi(options_.blend, interval, row, scanlines.begin + k, a[size_t(k)], b[size_t(k)], joint[size_t(k)],
               p.first - p.a);
    });
    for (int k = 0; k < scanlines.size(); ++k) sink.putEpi(row, scanlines.begin + k, joint[size_t(k)]);
  }

  // The EPIs of `table`'s scanlines in cam's share, as copies.
  std::vector<Image> draw(const ImageSlices& slices, const SliceTable& table, const ShearingCamera& cam, int row,
                          RenderStats& stats) {
    struct Keep final : FrameSink {
      std::vector<Image> epis;
      int first = 0;
      void putEpi(int, int scanline, const Image& epi) override { epis[size_t(scanline - first)] = epi; }
      void finish() override {}
    } keep;
    keep.first = cam.share().scanlines.begin;
    keep.epis.resize(size_t(cam.share().scanlines.size()));
    rasterizer_->rasterize(slices.vertices, table, cam, row, keep, stats);
    return std::move(keep.epis);
  }

  // Scanlines a band of renderIntervals holds: its EPIs (each interval's
  // three passes and, with several intervals, the assembled row) within
  // 256 MB.
  int bandScanlines(const ShearingCamera& cam, bool assembled) const {
    const double epi = double(cam.width()) * cam.views() * 4.0 * Image::channelBytes(type_);
    const double held = epi * ((options_.blend != Blend::None ? 3.0 : 1.0) + (assembled ? 1.0 : 0.0));
    return std::max(1, int(256e6 / held));
  }

  // The views [a, b] of cam as a camera of their own, on the given scanlines.
  static ShearingCamera intervalCamera(const ShearingCamera& cam, int a, int b, IndexRange scanlines) {
    CameraSpec spec = cam.spec();
    spec.trackLeft = cam.viewX(a);
    spec.trackRight = cam.viewX(b);
    spec.planeHeight = cam.planeHeight();
    RenderShare share = cam.share();
    share.scanlines = scanlines;
    share.views = {0, b - a + 1};
    return ShearingCamera(spec, cam.width(), cam.height(), b - a + 1, cam.rows()).withShare(share);
  }

  ImageSlices slice(const std::vector<SourceLayer>& layers, const ShearingCamera& cam, int row, RenderStats& stats) {
    ImageSlices slices;
    {
      ScopedStage s(stats.times, "slicing");
      slices = sliceSourceLayers(layers, cam, row,
                                 {.overlap = options_.overlap, .coalesce = options_.coalesce, .scene = &scene_,
                                  .splits = splits_, .fitRims = options_.blend != Blend::None});
    }
    countSlices(slices.table.sliceCount(), slices.pixels, stats);
    if (splits_ > 0) stats.counters["highlight_knots"] += double(slices.vertices.knots.size());
    return slices;
  }

  // Source views in GPU memory, sliced there: only the EPIs and the slice
  // table's offsets come back.
  void renderOnGpu(const ShearingCamera& cam, int row, FrameSink& sink, RenderStats& stats) {
    const bool refine = options_.acquire == Acquire::Hierarchical;
    const std::vector<double> xs = fixedSources(cam);
    store_.reset(cam.width(), cam.height(), (refine ? options_.budget : int(xs.size())) * options_.maxLayers);
    std::vector<StoredSource> sources;
    for (const double x : xs) sources.push_back(storeSource(cam, row, x, stats));
    if (refine && sources.size() == 2) refineOnGpu(cam, row, sources, stats);
    std::sort(sources.begin(), sources.end(), [](const StoredSource& a, const StoredSource& b) { return a.x < b.x; });
    for (const StoredSource& source : sources) stats.counters["layers"] += double(source.layers);
    // Between each two neighbouring sources, each half of the interval
    // from its near source's layers and the far source's nearest
    // (renderIntervals); the store's other layers stay outlines to meet.
    // Center: one source, drawn whole.
    std::vector<GpuPiece> pieces;
    if (sources.size() == 1) pieces.push_back({{0, cam.views() - 1, sources[0].layers, 0}, 0, 0});
    for (size_t k = 0; k + 1 < sources.size(); ++k) {
      const int a = viewAt(cam, sources[k].x), b = viewAt(cam, sources[k + 1].x);
      if (a < 0 || b <= a) fail("interp", "a source's eye is not a view of the set");
      for (const PieceLayers& p : pieceLayers(a, b, sources[k].layers, sources[k + 1].layers, halves()))
        pieces.push_back({p, sources[k].first, sources[k + 1].first});
    }
    const bool whole = pieces.size() == 1 && pieces[0].views.first == 0 && pieces[0].views.last == cam.views() - 1;
    std::vector<GpuImageSlices> slices;
    {
      ScopedStage s(stats.times, "slicing");
      gl::GpuClock::mark("image_slicing");
      for (const GpuPiece& piece : pieces) {
        const PieceLayers& p = piece.views;
        std::vector<uint8_t> keep(size_t(store_.count()), 0);
        std::fill_n(keep.begin() + piece.firstA, p.fromA, uint8_t(1));
        std::fill_n(keep.begin() + piece.firstB, p.fromB, uint8_t(1));
        // The near source's layers, then the far one's, as renderIntervals
        // lists them (sources added later lie after both in the store).
        std::vector<int> order;
        for (int k = 0; k < p.fromA; ++k) order.push_back(piece.firstA + k);
        for (int k = 0; k < p.fromB; ++k) order.push_back(piece.firstB + k);
        for (int k = 0; k < store_.count(); ++k)
          if (!keep[size_t(k)]) order.push_back(k);
        const ShearingCamera sub = whole ? cam : intervalCamera(cam, p.first, p.last, cam.share().scanlines);
        slices.push_back(gpuSlicer_->build(store_, sub, {options_.overlap, options_.coalesce}, keep, order));
      }
    }
    // Read once the slicer has waited on the GPU anyway: read between
    // sources, they stalled it.
    std::vector<SourceView> views;
    {
      ScopedStage s(stats.times, "source_readback");
      for (const StoredSource& source : sources)
        if (const int v = passesThrough() ? viewAt(cam, source.x) : -1; v >= 0)
          views.push_back({v, source.layers > 0 ? store_.readColor(source.first)
                                                : Image(cam.width(), cam.height(), PixelType::F32)});
    }
    for (const GpuImageSlices& piece : slices) countSlices(piece.table.sliceCount(), piece.pixels, stats);
    SourceViewSink out(sink, views);
    if (whole) return rasterizer_->rasterize(slices[0].vertices, slices[0].table, cam, row, out, stats);
    if (pieces.front().views.first != 0 || pieces.back().views.last != cam.views() - 1)
      fail("interp", "the source views do not reach both ends of the track");
    assemble(cam, row, int(slices.size()), out, [&](int k, IndexRange scanlines, std::vector<Image>& into) {
      const PieceLayers& p = pieces[size_t(k)].views;
      IntoViews pieceSink(into, scanlines.begin, p.first, cam.views());
      rasterizer_->rasterize(slices[size_t(k)].vertices, slices[size_t(k)].table,
                             intervalCamera(cam, p.first, p.last, scanlines), row, pieceSink, stats);
    });
  }

  // A source view whose layers are in the store: from `first` on, the
  // `layers` it keeps.
  struct StoredSource {
    double x;
    int first, layers;
  };
  // A piece of an interval, and where its two sources' layers start.
  struct GpuPiece {
    PieceLayers views;
    int firstA, firstB;
  };

  // One source's layers into the store, the visibility filter applied as
  // render()'s filter does on the host: the source keeps its layers up to
  // the first that the nearest hides whole (that one and those behind it
  // go), the hidden pixels of the others dropped in place.
  StoredSource storeSource(const ShearingCamera& cam, int row, double x, RenderStats& stats) {
    stats.counters["source_views"] += 1;
    StoredSource source{x, store_.count(), 0};
    gl::GpuClock::mark("acquire");
    source.layers =
        sources_->render(sourceCamera(cam), {x, cam.rowY(row)}, options_.maxLayers, trackWidth(cam), stats, store_);
    if (!options_.visibility || source.layers < 2) return source;
    ScopedStage s(stats.times, "visibility");
    const std::vector<LayerVisibility> seen = gpuVisibility_->hide(store_, cam, options_.overlap, source.first);
    for (int k = 1; k < source.layers; ++k) {
      const LayerVisibility& v = seen[size_t(source.first + k)];
      stats.counters["hidden_pixels"] += double(v.covered - v.kept);
      if (v.kept == 0) source.layers = k;
    }
    return source;
  }

  // refine() on the store: the holes two sources' layers leave halfway
  // between them counted by compute passes, one count read back a check.
  void refineOnGpu(const ShearingCamera& cam, int row, std::vector<StoredSource>& sources, RenderStats& stats) {
    refineTrack(
        cam, sources, stats,
        [&](int a, int b, int m) {
          std::vector<uint8_t> use(size_t(store_.count()), 0);
          for (const StoredSource& s : sources)
            if (s.x == cam.viewX(a) || s.x == cam.viewX(b)) std::fill_n(use.begin() + s.first, s.layers, uint8_t(1));
          return gpuVisibility_->holes(store_, use, cam, cam.viewX(m), options_.overlap);
        },
        [&](int m) { return storeSource(cam, row, cam.viewX(m), stats); });
  }

  bool halves() const { return options_.halves && options_.blend == Blend::None; }

  // Whether the views at source eyes are the sources' images: not where
  // highlights are split off the source colours (they are added per view).
  bool passesThrough() const { return splits_ == 0; }

  // The camera source views are rendered through: the share's scanlines
  // only, since scanline j of every EPI comes from row j of the sources
  // alone; all of them where hole counts or the visibility filter judge
  // whole views (the job's sources, and so its images, must not depend on
  // the share).
  ShearingCamera sourceCamera(const ShearingCamera& cam) const {
    if (options_.acquire != Acquire::Hierarchical && !options_.visibility) return cam;
    RenderShare whole = cam.share();
    whole.scanlines = {0, cam.height()};
    return cam.withShare(whole);
  }

  static void countSlices(size_t slices, size_t pixels, RenderStats& stats) {
    stats.counters["slices"] += double(slices);
    stats.counters["slice_pixels"] += double(pixels);
    const double bytes = double(slices * sizeof(Slice));
    stats.counters["slice_table_bytes"] = std::max(stats.counters["slice_table_bytes"], bytes);
  }

  static double trackWidth(const ShearingCamera& cam) {
    return std::abs(cam.spec().trackRight - cam.spec().trackLeft);
  }

  // Camera x of the source views center and dual acquisition render (the
  // pair hierarchical acquisition starts from).
  std::vector<double> fixedSources(const ShearingCamera& cam) const {
    const int n = cam.views();
    if (options_.acquire == Acquire::Center || n == 1) return {0.5 * (cam.viewX(0) + cam.viewX(n - 1))};
    return {cam.viewX(0), cam.viewX(n - 1)};
  }

  std::vector<Source> acquire(const ShearingCamera& cam, int row, RenderStats& stats) {
    std::vector<Source> sources;
    for (double x : fixedSources(cam)) sources.push_back(render(cam, row, x, stats));
    if (options_.acquire == Acquire::Hierarchical && sources.size() == 2) refine(cam, row, sources, stats);
    return sources;
  }

  void refine(const ShearingCamera& cam, int row, std::vector<Source>& sources, RenderStats& stats) {
    refineTrack(
        cam, sources, stats,
        [&](int a, int b, int m) {
          std::vector<const SourceLayer*> near;
          for (const Source& s : sources)
            if (s.x == cam.viewX(a) || s.x == cam.viewX(b))
              for (const SourceLayer& l : s.layers) near.push_back(&l);
          return countHoles(near, cam, cam.viewX(m), options_.overlap);
        },
        [&](int m) { return render(cam, row, cam.viewX(m), stats); });
  }

  // refineTrack (mvr/views/track_refinement.h) with this back end's budget and
  // tolerance, its hole counts timed as the visibility stage; add(m)
  // returns the source at view m.
  template <class S, class Holes, class Add>
  void refineTrack(const ShearingCamera& cam, std::vector<S>& sources, RenderStats& stats, Holes&& holes, Add&& add) {
    mvr::refineTrack(
        cam, options_.holeFraction, options_.budget, int(sources.size()), stats,
        [&](int a, int b, int m) {
          ScopedStage s(stats.times, "visibility");
          return holes(a, b, m);
        },
        [&](int m) { sources.push_back(add(m)); });
  }

  Source render(const ShearingCamera& cam, int row, double x, RenderStats& stats) {
    stats.counters["source_views"] += 1;
    LayerFilter visible;
    if (options_.visibility)
      visible = [&](const std::vector<SourceLayer>& nearer, SourceLayer& layer) {
        if (nearer.empty()) return true;
        ScopedStage s(stats.times, "visibility");
        const auto before = std::count_if(layer.depth.begin(), layer.depth.end(), [](float d) { return d > 0.0f; });
        const long kept = hideInvisible(nearer.front(), layer, cam, options_.overlap);
        stats.counters["hidden_pixels"] += double(before - kept);
        return kept > 0;
      };
    return {x, sources_->render(sourceCamera(cam), {x, cam.rowY(row)}, options_.maxLayers, trackWidth(cam), stats,
                                visible)};
  }

  InterpOptions options_;
  PixelType type_;
  const Scene& scene_;
  int splits_;  // options_.splits where the scene has highlights, else 0
  std::unique_ptr<SourceLayerRenderer> sources_;
  std::unique_ptr<EpiRasterizer> rasterizer_;
  std::optional<GpuImageSlicer> gpuSlicer_;  // when layers stay on the GPU
  std::optional<GpuVisibility> gpuVisibility_;  // with them: visibility, hole counts
  DeviceLayers store_;
  std::vector<Image> assembled_;  // a band's EPIs of all views (assemble), kept for the next
};

}  // namespace

std::unique_ptr<Renderer> makeInterpRenderer(const Scene& scene, PixelType type,
                                             const InterpOptions& options) {
  return std::make_unique<InterpRenderer>(scene, type, options);
}

}  // namespace mvr
