#pragma once
// Reordering between EPI-major and view-major frames (a sink concern, not a
// renderer's): view i's scanline j is EPI j's row i. A row of views is one
// volume, W x H x N pixels; it is held in memory when it fits the memory
// budget, and otherwise in a scratch file that a transpose reads back in
// runs of rows, a group of output frames at a time (issue 15: a printer's
// 1000 views of 1920x1080 are 8.3 GB). Both ways give the same bytes.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mvr/renderer.h"
#include "mvr/scratch_file.h"

namespace mvr {

// How much of a row's volume a reordering sink may hold.
struct ReorderMemory {
  size_t budget = 0;       // bytes of frames held at once; 0: no limit
  std::string scratchDir;  // where the volume goes when it exceeds the budget
  // A volume of this size goes through the scratch file.
  bool spills(size_t volumeBytes) const { return budget != 0 && volumeBytes > budget; }
  // What a volume of this size holds in memory at most.
  size_t held(size_t volumeBytes) const { return spills(volumeBytes) ? budget : volumeBytes; }
};

// N input frames of M rows each, in, become M output frames of N rows each,
// out: output j's row i is input i's row j.
class FrameTranspose {
 public:
  FrameTranspose(int inputs, int rowsPerInput, int width, PixelType type,
                 const ReorderMemory& memory);
  // Input i; true once all inputs of the volume are in.
  bool put(int index, const Image& frame);
  // Hands on every output in order, then starts a new volume.
  void emit(const std::function<void(int, const Image&)>& out);
  // Output frames held at once: all of them in memory, fewer from scratch.
  int outputsPerPass() const { return int(outputs_.size()); }
  bool usesScratch() const { return scratch_ != nullptr; }
  // How the frames met, as manifests say: "scratch file" or "volume in memory".
  const char* method() const { return usesScratch() ? "scratch file" : "volume in memory"; }
  // For a command's summary line: "" in memory, else the passes' size.
  std::string scratchNote() const;

 private:
  void emitFromScratch(const std::function<void(int, const Image&)>& out);
  int inputs_, rowsPerInput_;
  size_t inputBytes_, rowBytes_;
  std::vector<Image> outputs_;  // all outputs, or one pass's group of them
  std::unique_ptr<ScratchFile> scratch_;
  int received_ = 0;
};

// Collects the EPIs of one row of views and hands the views on once all
// scanlines have arrived.
class EpisToViews final : public FrameSink {
 public:
  EpisToViews(FrameSink& inner, int width, int height, int views, PixelType type,
              const ReorderMemory& memory = {});
  void putEpi(int row, int scanline, const Image& epi) override;
  void finish() override { inner_.finish(); }
  const FrameTranspose& transpose() const { return volume_; }

 private:
  FrameSink& inner_;
  int height_, views_;
  FrameTranspose volume_;
  int row_ = 0;
};

// Collects all views of one row, then hands on its EPIs.
class ViewsToEpis final : public FrameSink {
 public:
  ViewsToEpis(FrameSink& inner, int width, int height, int views, PixelType type,
              const ReorderMemory& memory = {});
  void putView(int row, int view, const Image& image) override;
  void finish() override { inner_.finish(); }
  const FrameTranspose& transpose() const { return volume_; }

 private:
  FrameSink& inner_;
  int height_, views_;
  FrameTranspose volume_;
  int row_ = 0;
};

}  // namespace mvr
