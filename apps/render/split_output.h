#pragma once
// The output side of a render split over the ranks of an MPI job
// (apps/cli/job_split.h): each rank renders its share of the frames; frames
// that must change order (EPIs to views, views to EPIs) or meet in a quilt
// go through one shared scratch file (MPI-IO) in the order they were
// rendered, and each rank then reads back and encodes its own run of the
// output frames, so no rank ever holds the set. Rows a rank renders whole
// it reorders itself, as one process does. Rank 0 writes the quilt
// and the manifest. The images are the single-process render's bytes.
// A stream (toViews false) is written the same way, its records at their
// offsets.
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "apps/cli/job_split.h"
#include "apps/render/mpi_session.h"
#include "mvr/frames/volume.h"
#include "mvr/frames/frame_sinks.h"

namespace mvr::app {

struct SplitOutputSpec {
  FrameOrder rendered = FrameOrder::Epi;  // the renderer's order
  bool toViews = true;                    // the set holds views, else EPIs
  PixelType type = PixelType::Srgb8;
  std::string dir;                        // the output folder (the scratch file lives there)
  bool quilt = false;                     // a quilt is written (by rank 0)
  bool frames = true;                     // the set's frames are written (not --quilt-only)
  size_t memoryBudget = size_t(256) << 20;  // output frames held at once, per rank
  ReorderMemory reorder;                  // whole rows per rank: how a row is reordered
  std::string scratchName = ".mvr_split_volume";  // in dir; one per SplitOutput alive at once
};

class SplitOutput {
 public:
  // Collective: opens the shared scratch file when the orders differ or a
  // quilt is written (rank 0 passes it; the others null). `set` takes this
  // rank's frames of the set in its order: an image set's writer, or a
  // stream's records.
  SplitOutput(MpiSession& mpi, const ShearingCamera& camera, const JobSplit& split, const SplitOutputSpec& spec,
              FrameSink& set, QuiltSink* quilt);
  ~SplitOutput();

  const JobSplit& split() const { return split_; }
  // What this rank renders, in order.
  const std::vector<RenderShare>& shares() const { return split_.shares[size_t(mpi_.rank())]; }
  // Where this rank's rendered frames go.
  FrameSink& sink() { return *sink_; }
  // After every rank rendered (the ranks agreed): the output frames this
  // rank encodes, from the scratch file, and on rank 0 the quilt's views.
  void assemble();
  // What the manifest records of the job.
  nlohmann::json info() const;

 private:
  class Router;
  // Output frames [first, last) of the whole set in the set's order,
  // read back from the scratch file, handed to out(row, index, image).
  void readBack(bool views, long first, long last, const std::function<void(int, int, const Image&)>& out);

  MpiSession& mpi_;
  ShearingCamera camera_;
  JobSplit split_;
  SplitOutputSpec spec_;
  FrameSink& writer_;
  QuiltSink* quilt_;
  bool direct_ = false;     // rendered in the set's order: frames go to the writer as they come
  bool exchanges_ = false;  // the grid's output frames are read back from the scratch file
  std::unique_ptr<SharedFile> volume_;
  std::unique_ptr<FrameSink> reorder_;  // the rows a rank renders whole: reordered here
  std::unique_ptr<FrameSink> sink_;
};

}  // namespace mvr::app
