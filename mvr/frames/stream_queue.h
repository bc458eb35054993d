#pragma once
// The EPI stream behind a bounded queue: the renderer hands over EPIs and
// goes on while a writer thread sends them; when the consumer is slow the
// queue fills and putEpi blocks (backpressure), so memory stays at
// `capacity` EPIs however long the render.
#include <condition_variable>
#include <deque>
#include <exception>
#include <mutex>
#include <ostream>
#include <thread>
#include <vector>

#include "mvr/frames/epi_stream.h"
#include "mvr/image_pool.h"

namespace mvr {

class QueuedEpiStream final : public FrameSink {
 public:
  QueuedEpiStream(std::ostream& out, const EpiStreamHeader& header, size_t capacity);
  ~QueuedEpiStream() override;
  void putEpi(int row, int scanline, const Image& epi) override;
  // Takes the EPI's pixels for the queue and leaves a written EPI's
  // image of the same size in their place: no copy once the writer has
  // given images back.
  void putEpiInPlace(int row, int scanline, Image& epi) override;
  // Sends what is queued and flushes; rethrows the writer's error, if any.
  void finish() override;
  size_t highWater() const { return highWater_; }

 private:
  struct Frame {
    int row, scanline;
    Image epi;
  };
  void writerLoop(std::ostream& out, EpiStreamHeader header);
  void enqueue(int row, int scanline, Image&& epi);

  size_t capacity_, highWater_ = 0;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Frame> queue_;
  SpareImages spares_;  // written EPIs' images, to hold the next ones
  bool closing_ = false, writerDone_ = false;
  std::exception_ptr error_;
  std::thread writer_;
};

}  // namespace mvr
