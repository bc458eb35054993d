#include "apps/render/split_output.h"

#include <algorithm>
#include <cstring>
#include <filesystem>

#include "mvr/frames/volume.h"
#include "mvr/error.h"

namespace mvr::app {
namespace {

std::span<const std::byte> bytesOf(const Image& image) { return std::as_bytes(std::span(image.bytes)); }

}  // namespace

// Hands each rendered frame on to the set (the writer, or a reordering
// sink in front of it) and to the scratch file when frames must meet
// another rank's.
class SplitOutput::Router final : public FrameSink {
 public:
  Router(SplitOutput& out, FrameSink* set) : out_(out), set_(set) {}
  void putView(int row, int view, const Image& image) override {
    if (toSet(row)) set_->putView(row, view, image);
    if (toVolume(row)) out_.volume_->write(offset(row, view, image), bytesOf(image));
  }
  void putEpi(int row, int scanline, const Image& epi) override {
    if (toSet(row)) set_->putEpi(row, scanline, epi);
    if (toVolume(row)) out_.volume_->write(offset(row, scanline, epi), bytesOf(epi));
  }

 private:
  // Frames in the set's order, and a rank's whole rows reordered here.
  bool toSet(int row) const { return set_ && (out_.direct_ || row < out_.split_.gridBegin()); }
  // Every frame for a quilt; the grid's for the exchange.
  bool toVolume(int row) const {
    return out_.volume_ && (out_.spec_.quilt || (out_.exchanges_ && row >= out_.split_.gridBegin()));
  }
  // Frames in the order they were rendered: row by row, each row's frames by index.
  uint64_t offset(int row, int index, const Image& frame) const {
    const ShearingCamera& cam = out_.camera_;
    const int perRow = out_.spec_.rendered == FrameOrder::Epi ? cam.height() : cam.views();
    return (uint64_t(row) * perRow + uint64_t(index)) * frame.bytes.size();
  }
  SplitOutput& out_;
  FrameSink* set_;
};

SplitOutput::SplitOutput(MpiSession& mpi, const ShearingCamera& camera, const JobSplit& split,
                         const SplitOutputSpec& spec, FrameSink& writer, QuiltSink* quilt)
    : mpi_(mpi), camera_(camera), split_(split), spec_(spec), writer_(writer), quilt_(quilt) {
  direct_ = (spec.rendered == FrameOrder::View) == spec.toViews;
  exchanges_ = spec.frames && !direct_ && split.gridBegin() < camera.rows();
  if (exchanges_ || spec.quilt)
    volume_ = std::make_unique<SharedFile>((std::filesystem::path(spec.dir) / spec.scratchName).string());
  FrameSink* set = nullptr;
  if (spec.frames && direct_) {
    set = &writer;
  } else if (spec.frames && split.wholeRows > 0) {
    const int w = camera.width(), h = camera.height(), n = camera.views();
    if (spec.toViews) reorder_ = std::make_unique<EpisToViews>(writer, w, h, n, spec.type, spec.reorder);
    else reorder_ = std::make_unique<ViewsToEpis>(writer, w, h, n, spec.type, spec.reorder);
    set = reorder_.get();
  }
  sink_ = std::make_unique<Router>(*this, set);
}

SplitOutput::~SplitOutput() = default;

void SplitOutput::assemble() {
  if (exchanges_) {
    // This rank's run of the grid's output frames, by count.
    const long perRow = spec_.toViews ? camera_.views() : camera_.height();
    const long first = perRow * split_.gridBegin(), total = perRow * camera_.rows() - first;
    const long k = mpi_.rank(), ranks = mpi_.ranks();
    readBack(spec_.toViews, first + total * k / ranks, first + total * (k + 1) / ranks,
             [&](int row, int index, const Image& f) {
      spec_.toViews ? writer_.putView(row, index, f) : writer_.putEpi(row, index, f);
    });
  }
  if (quilt_)
    readBack(true, 0, long(camera_.views()) * camera_.rows(),
             [&](int row, int view, const Image& f) { quilt_->putView(row, view, f); });
}

void SplitOutput::readBack(bool views, long first, long last,
                           const std::function<void(int, int, const Image&)>& out) {
  const ShearingCamera& cam = camera_;
  const bool renderedViews = spec_.rendered == FrameOrder::View;
  const int w = cam.width(), perRow = views ? cam.views() : cam.height();
  const int inputs = renderedViews ? cam.views() : cam.height();  // rendered frames per row
  const int frameRows = views ? cam.height() : cam.views();       // rows of an output frame
  const size_t rowBytes = size_t(w) * 4 * Image::channelBytes(spec_.type);
  const size_t inputBytes = rowBytes * size_t(renderedViews ? cam.height() : cam.views());
  const long group = std::clamp<long>(long(spec_.memoryBudget / (rowBytes * frameRows)), 1, 4096);
  std::vector<Image> frames;
  std::vector<std::byte> run;
  for (long g = first; g < last;) {
    const int row = int(g / perRow), index = int(g % perRow);
    const int n = int(std::min({group, last - g, long(perRow - index)}));
    frames.resize(size_t(n), Image(w, frameRows, spec_.type));
    const uint64_t rowBase = uint64_t(row) * inputs;
    if (views == renderedViews) {
      // The frames as rendered.
      for (int k = 0; k < n; ++k)
        volume_->read((rowBase + uint64_t(index + k)) * inputBytes, std::as_writable_bytes(std::span(frames[size_t(k)].bytes)));
    } else {
      // Output frame k's row i is rendered frame i's row index + k: one
      // run of n rows from every rendered frame.
      run.resize(rowBytes * size_t(n));
      for (int i = 0; i < inputs; ++i) {
        volume_->read((rowBase + uint64_t(i)) * inputBytes + uint64_t(index) * rowBytes, run);
        for (int k = 0; k < n; ++k) std::memcpy(frames[size_t(k)].row(i), run.data() + size_t(k) * rowBytes, rowBytes);
      }
    }
    for (int k = 0; k < n; ++k) out(row, index + k, frames[size_t(k)]);
    g += n;
  }
}

nlohmann::json SplitOutput::info() const {
  nlohmann::json shares = nlohmann::json::array();
  for (const std::vector<RenderShare>& rank : split_.shares) {
    nlohmann::json list = nlohmann::json::array();
    for (const RenderShare& s : rank) {
      const IndexRange part = split_.axis == "scanlines" ? s.scanlines : s.views;
      list.push_back({{"rows", {s.rows.begin, s.rows.end}}, {split_.axis, {part.begin, part.end}}});
    }
    shares.push_back(list);
  }
  return {{"ranks", mpi_.ranks()},
          {"whole_rows_per_rank", split_.wholeRows},
          {"grid", {{"row_groups", split_.rowGroups}, {"parts_per_row", split_.parts}}},
          {"split", split_.axis},
          {"estimated_imbalance", split_.imbalance},
          {"shares", shares},
          {"scratch_file", volume_ != nullptr}};
}

}  // namespace mvr::app
