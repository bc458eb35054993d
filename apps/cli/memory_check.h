#pragma once
// A job's memory, decided before any work starts (issues 15 and 16). A
// reordering sink holds a row of frames in memory up to a budget
// (`--memory`, default half the available memory) and beyond it goes
// through a scratch file; a quilt is held whole. What cannot fit, in
// memory or on the scratch disk, is refused in one line naming the size
// and what to change, instead of growing until the kernel kills it.
#include <cstddef>
#include <string>

#include <CLI/CLI.hpp>

#include "mvr/frames/volume.h"

namespace mvr::app {

// What the command holds beside the renderer's own buffers.
struct HeldFrames {
  size_t reorderBytes = 0;  // frames held for reordering (in memory)
  size_t quiltBytes = 0;    // every view tiled in one image
};

// Bytes the system can still give (MemAvailable), or 0 when unknown.
size_t availableMemory();

// Throws mvr::Error when held frames exceed `available` (0: unknown, no
// check). `advice` names the ways out, e.g. "use --order epi or mvr stream".
void checkHeldFramesFit(const HeldFrames& held, size_t available, const std::string& advice);

// "1G", "512M", "1.5GiB", "64k" or plain bytes (binary units); errors name
// the flag.
size_t parseByteSize(const std::string& flag, const std::string& text);

// --memory BUDGET and --scratch DIR.
struct MemoryFlags {
  std::string budget, scratch;
  void add(CLI::App& app, const std::string& scratchDefault);
  // The budget in bytes: --memory, or half the available memory (0 when
  // that is unknown: no limit).
  size_t budgetBytes() const;
  // What a reordering sink may hold: the budget less what the encoders
  // hold in flight (`inFlight` frames of `frameBytes`, queued copies and
  // their encoded files). Throws when the budget cannot hold one frame
  // beside them.
  ReorderMemory reorder(size_t frameBytes, int inFlight, const std::string& scratchDefault) const;
};

// Throws naming the folder when a scratch volume of `bytes` exceeds the
// free space of dir's file system.
void checkScratchFits(size_t bytes, const std::string& dir);

}  // namespace mvr::app
