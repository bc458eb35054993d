#pragma once
// The frame chain: everything a rendered frame passes through on its way
// to where it is kept, built in one place from a description of the
// output. Outermost first:
//   renderer -> [supersampling] -> [predistortion] -> [background]
//            -> [depth packing] -> [reorder: EPIs <-> views, or EPI rows
//               straight into PNG views] -> [tee: frames and quilt]
//            -> destination
// The per-pixel stages (predistortion, background) give the same bytes
// before or after a reorder. render, stream, synthesize, the split job,
// the depth pass, the bench and mvr-consume all build theirs here.
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "mvr/depth.h"
#include "mvr/frames/frame_sinks.h"
#include "mvr/frames/supersampling.h"
#include "mvr/frames/volume.h"

namespace mvr {

class ImageSetWriter;
class EpisToPngViews;
class Manifest;

// 8-bit (or float into PNG) views of a set made from EPI rows, with no
// volume: the encoders' queue and the files' bytes they may hold.
struct PngRows {
  size_t filesBudget = 0;
  int queueLength = 4;
};

// Where PNG rows can make a set's views from EPIs of `type` within the
// memory budget; nothing where the set is not such PNGs or the budget has
// no room. onPool: the renderer fills EPIs on the pool the encoders use,
// so a long queue would only hold memory.
std::optional<PngRows> planPngRows(const Manifest& set, PixelType type, size_t budget, bool onPool);

// Where the chain's frames end.
struct FrameDestination {
  FrameSink* sink = nullptr;       // the set's writer, a stream, a split job's router
  ImageSetWriter* set = nullptr;   // the same writer, where PNG rows may feed it directly
  QuiltSink* quilt = nullptr;      // a quilt beside the frames
  bool frames = true;              // false: only the quilt (--quilt-only)
};

struct FrameChainSpec {
  FrameOrder rendered = FrameOrder::Epi;   // what the renderer hands on
  FrameOrder delivered = FrameOrder::View; // what the destination takes
  int width = 0, height = 0, views = 0;    // the set's frames, after supersampling
  PixelType type = PixelType::Srgb8;       // of the frames reordered
  ReorderMemory reorder;
  Supersampling aa;
  std::optional<glm::vec4> background;
  std::vector<float> predistortion;        // empty: none
  std::optional<DepthColoring> depth;      // pack frames into depths (mvr/depth.h)
  std::optional<PngRows> pngRows;          // EPIs to a PNG set's views by rows
};

class FrameChain {
 public:
  FrameChain(const FrameDestination& destination, const FrameChainSpec& spec);
  ~FrameChain();
  FrameChain(const FrameChain&) = delete;
  FrameChain& operator=(const FrameChain&) = delete;

  // Where the renderer puts its frames.
  FrameSink& entry() { return *entry_; }
  // The manifest's "reorder" entry; null where nothing reorders.
  nlohmann::json reorderInfo() const;
  // How a reorder met its frames, for a command's summary line ("" in memory).
  std::string scratchNote() const;

 private:
  template <class Sink, class... Args>
  Sink& push(Args&&... args);
  void addReorder(const FrameDestination& destination);

  FrameChainSpec spec_;
  std::vector<std::unique_ptr<FrameSink>> sinks_;  // innermost first
  FrameSink* entry_ = nullptr;
  const FrameTranspose* transpose_ = nullptr;
  const EpisToPngViews* pngViews_ = nullptr;
};

}  // namespace mvr
