#pragma once
// Reads rendered pixels back while the GPU draws the next batch. A
// renderer asks for rows of a target to be read into host memory it owns,
// then submits the batch with what to do once they are there; on a GPU
// the reads go through a ring of persistently mapped pixel-pack buffers
// (one fence per batch) and land in place when the ring comes back round
// to the batch's slot (slots - 1 batches later) or at drain(). Batches
// complete in submission order, so sinks see frames in order while the
// GPU is busy with later ones. On a GL that renders on the CPU
// (gl::rendersOnCpu) reads are synchronous anyway: they go straight to
// their destination and each batch completes at submit.
#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "mvr/gl/gl_handles.h"
#include "mvr/gl/render_target.h"

namespace mvr {

// Whether rings stage their reads: by the GL implementation (Auto), or
// always or never, process-wide (tests run the staged path on llvmpipe).
enum class ReadbackStaging { Auto, Always, Never };
void setReadbackStaging(ReadbackStaging staging);

class ReadbackRing {
 public:
  using Done = std::function<void()>;

  // slotBytes: the most one batch reads. Needs a current GL context.
  explicit ReadbackRing(size_t slotBytes, int slots = 3);
  ~ReadbackRing();
  ReadbackRing(const ReadbackRing&) = delete;
  ReadbackRing& operator=(const ReadbackRing&) = delete;

  bool staged() const { return !slots_.empty(); }
  // Rows [y, y + h) of a 2D target, or one layer of a layered target,
  // into dst (rows of the target's width in its pixel type); dst must stay
  // valid until the batch is done.
  void readRows(const RenderTarget& target, int y, int h, std::byte* dst);
  void readLayer(const RenderTarget& target, int layer, std::byte* dst);
  // Rows [y, y + h dsts.size()) in one read: h rows into each of dsts in
  // turn (a batch of stacked EPIs; one call instead of one per EPI).
  void readRowRuns(const RenderTarget& target, int y, int h, std::span<std::byte* const> dsts);
  // `bytes` of a storage buffer that shaders wrote, split evenly among
  // dsts (a batch of EPIs a compute pass filled).
  void readBuffer(GLuint buffer, size_t bytes, std::span<std::byte* const> dsts);
  // Ends the batch: `done` runs once its reads have landed.
  void submit(Done done);
  // Completes every submitted batch, in order.
  void drain();
  // Seconds spent waiting for fences and copying: the GPU work and
  // transfers the CPU could not hide.
  double waitSeconds() const { return waitSeconds_; }

 private:
  struct Copy {
    size_t at, bytes;
    std::byte* dst;
  };
  struct Slot {
    gl::Buffer buffer;
    const std::byte* bytes = nullptr;
    GLsync fence = nullptr;
    size_t used = 0;
    std::vector<Copy> copies;
    Done done;
  };
  void read(const RenderTarget& target, GLuint framebuffer, int y, int h, std::span<std::byte* const> dsts);
  size_t reserve(size_t bytes, std::span<std::byte* const> dsts);
  void finish(Slot& slot);
  void copyOut(const Slot& slot);

  size_t slotBytes_;
  std::vector<Slot> slots_;  // empty: reads are synchronous
  size_t current_ = 0;
  double waitSeconds_ = 0.0;
  gl::Framebuffer layerReader_;  // attaches one layer at a time
};

}  // namespace mvr
