#pragma once
// The command lines of render, stream and synthesize on CLI11, and the job
// each describes (render_job.h).
#include <optional>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

#include "apps/render/render_job.h"
#include "apps/cli/sequence_flags.h"
#include "mvr/images/image_file.h"

namespace mvr::app {

class RenderFlags {
 public:
  explicit RenderFlags(RenderCommand command) : command_(command) {}
  // The command's description and name, for its CLI::App.
  std::string description() const;
  std::string name() const;
  void add(CLI::App& app);
  // After parsing: every value resolved and checked, before any GL or
  // file work except the references a synthesis starts from.
  RenderJob describe(const CLI::App& app) const;

 private:
  void addShared(CLI::App& app);
  void addOutputShape(CLI::App& app);
  void addRenderOwn(CLI::App& app);
  void addSynthesizeOwn(CLI::App& app);
  void addStreamOwn(CLI::App& app);

  RenderCommand command_;
  BackendFlags backend_;
  std::string scene_;
  int views_ = 16, rows_ = 1, queue_ = 8, compression_ = kDefaultPngCompression;
  std::optional<int> bits_;  // unset: 8 for png and tiff, 32 (float) for exr
  std::pair<int, int> size_{320, 240};
  std::string out_ = "out", format_ = "png", order_ = "view", gl_ = "auto";
  std::string stream_, quilt_, predistort_, codec_;
  bool strict_ = false, linear_ = false, depth_ = false, quiltOnly_ = false;
  LookOptions look_;
  std::string tonemap_ = "none";
  std::string native_;  // the display's calibration file
  std::string splitBy_ = "cost";  // under mpirun: scanline bands by estimated cost or by count
  MemoryFlags memory_;
  std::string from_;      // synthesize: the references' folder
  std::string warpPath_;  // synthesize: WarpOptions::path by name
  WarpOptions warp_;
  CameraFlags camera_;
  Supersampling aa_;
  SequenceFlags sequence_;
};

}  // namespace mvr::app
