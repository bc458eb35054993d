#include "mvr/frames/frame_chain.h"

#include "mvr/frames/png_views.h"
#include "mvr/images/image_set.h"

namespace mvr {

namespace {

// The depth pass's frames, views or EPIs, packed into their depths
// (mvr/depth.h) as they come, so that what reorders or exchanges them
// moves 4 bytes a pixel instead of the float colour's 16.
class DepthPacker final : public FrameSink {
 public:
  DepthPacker(FrameSink& inner, const DepthColoring& coloring) : inner_(inner), coloring_(coloring) {}
  void putView(int row, int view, const Image& image) override { inner_.putView(row, view, pack(image)); }
  void putEpi(int row, int scanline, const Image& epi) override { inner_.putEpi(row, scanline, pack(epi)); }
  void finish() override { inner_.finish(); }

 private:
  const Image& pack(const Image& frame) {
    packDepth(frame, coloring_, packed_);
    return packed_;
  }
  FrameSink& inner_;
  DepthColoring coloring_;
  Image packed_;
};

}  // namespace

std::optional<PngRows> planPngRows(const Manifest& set, PixelType type, size_t budget, bool onPool) {
  const size_t files = EpisToPngViews::filesBudget(set, type, budget);
  if (!EpisToPngViews::handles(set, type) || files == 0) return std::nullopt;
  return PngRows{files, onPool ? 4 : EpisToPngViews::queueLength(set, type, budget)};
}

template <class Sink, class... Args>
Sink& FrameChain::push(Args&&... args) {
  auto sink = std::make_unique<Sink>(std::forward<Args>(args)...);
  Sink& added = *sink;
  sinks_.push_back(std::move(sink));
  entry_ = &added;
  return added;
}

FrameChain::FrameChain(const FrameDestination& destination, const FrameChainSpec& spec) : spec_(spec) {
  entry_ = destination.sink;
  if (destination.quilt) {
    if (destination.frames) push<TeeSink>(std::vector<FrameSink*>{destination.sink, destination.quilt});
    else entry_ = destination.quilt;
  }
  addReorder(destination);
  if (spec.depth) push<DepthPacker>(*entry_, *spec.depth);
  if (spec.background) push<BackgroundSink>(*entry_, *spec.background);
  if (!spec.predistortion.empty()) push<PredistortSink>(*entry_, spec.predistortion);
  if (spec.aa.active()) push<SupersampleSink>(*entry_, spec.aa, spec.width, spec.height, spec.views);
}

// Outermost first: each sink goes before the one it hands frames to.
FrameChain::~FrameChain() {
  while (!sinks_.empty()) sinks_.pop_back();
}

// Only where the renderer's natural order is not the one asked for.
void FrameChain::addReorder(const FrameDestination& destination) {
  const FrameChainSpec& s = spec_;
  if (s.rendered == s.delivered) return;
  if (s.rendered == FrameOrder::Epi && destination.quilt && entry_ == destination.quilt) return;  // takes EPIs
  if (s.rendered == FrameOrder::View) {
    transpose_ = &push<ViewsToEpis>(*entry_, s.width, s.height, s.views, s.type, s.reorder).transpose();
  } else if (s.pngRows && destination.set && !destination.quilt) {
    pngViews_ = &push<EpisToPngViews>(*destination.set, s.type, s.pngRows->filesBudget, s.pngRows->queueLength);
  } else {
    transpose_ = &push<EpisToViews>(*entry_, s.width, s.height, s.views, s.type, s.reorder).transpose();
  }
}

nlohmann::json FrameChain::reorderInfo() const {
  if (transpose_)
    return {{"method", transpose_->method()},
            {"budget_bytes", spec_.reorder.budget},
            {"scratch_file", transpose_->usesScratch()},
            {"frames_per_pass", transpose_->outputsPerPass()}};
  if (pngViews_)
    return {{"method", EpisToPngViews::kMethod},
            {"budget_bytes", spec_.reorder.budget},
            {"scratch_file", false},
            {"files_to_disk_before_done", pngViews_->spills()}};
  return nullptr;
}

std::string FrameChain::scratchNote() const { return transpose_ ? transpose_->scratchNote() : ""; }

}  // namespace mvr
