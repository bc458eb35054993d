#pragma once
// A job's memory, estimated before any work starts (issue 16): the frames a
// reordering sink or a quilt holds at once. A job that cannot fit is refused
// in one line, naming the size and what to change, instead of growing until
// the kernel kills it.
#include <cstddef>
#include <string>

namespace mvr::app {

// What the command holds beside the renderer's own buffers.
struct HeldFrames {
  size_t reorderBytes = 0;  // one row of views (or EPIs) collected for reordering
  size_t quiltBytes = 0;    // every view tiled in one image
};

// Bytes the system can still give (MemAvailable), or 0 when unknown.
size_t availableMemory();

// Throws mvr::Error when held frames exceed `available` (0: unknown, no
// check). `advice` names the ways out, e.g. "use --order epi or mvr stream".
void checkHeldFramesFit(const HeldFrames& held, size_t available, const std::string& advice);

}  // namespace mvr::app
