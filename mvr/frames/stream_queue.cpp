#include "mvr/frames/stream_queue.h"

#include "mvr/error.h"

namespace mvr {

QueuedEpiStream::QueuedEpiStream(std::ostream& out, const EpiStreamHeader& header, size_t capacity)
    : capacity_(std::max<size_t>(1, capacity)),
      writer_([this, &out, header] { writerLoop(out, header); }) {}

QueuedEpiStream::~QueuedEpiStream() {
  {
    std::lock_guard lock(mutex_);
    closing_ = true;
  }
  changed_.notify_all();
  if (writer_.joinable()) writer_.join();
}

void QueuedEpiStream::writerLoop(std::ostream& out, EpiStreamHeader header) {
  try {
    EpiStreamWriter stream(out, header);
    for (;;) {
      Frame f;
      {
        std::unique_lock lock(mutex_);
        changed_.wait(lock, [&] { return !queue_.empty() || closing_; });
        if (queue_.empty()) break;
        f = std::move(queue_.front());
        queue_.pop_front();
      }
      changed_.notify_all();  // room for the producer
      stream.putEpi(f.row, f.scanline, f.epi);
      spares_.giveBack(std::move(f.epi));
    }
    stream.finish();
  } catch (...) {
    std::lock_guard lock(mutex_);
    error_ = std::current_exception();
  }
  {
    std::lock_guard lock(mutex_);
    writerDone_ = true;
  }
  changed_.notify_all();
}

// Into an image the writer is done with when there is one
// (mvr/image_pool.h); in place, that image takes the EPI's pixels.
void QueuedEpiStream::putEpi(int row, int scanline, const Image& epi) {
  enqueue(row, scanline, spares_.hold(epi));
}

void QueuedEpiStream::putEpiInPlace(int row, int scanline, Image& epi) {
  enqueue(row, scanline, spares_.hold(epi, &epi));
}

void QueuedEpiStream::enqueue(int row, int scanline, Image&& epi) {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [&] { return queue_.size() < capacity_ || writerDone_; });
  if (writerDone_) {
    if (error_) std::rethrow_exception(error_);
    fail("stream", "writer stopped early");
  }
  queue_.push_back({row, scanline, std::move(epi)});
  highWater_ = std::max(highWater_, queue_.size());
  lock.unlock();
  changed_.notify_all();
}

void QueuedEpiStream::finish() {
  {
    std::lock_guard lock(mutex_);
    closing_ = true;
  }
  changed_.notify_all();
  if (writer_.joinable()) writer_.join();
  if (error_) std::rethrow_exception(error_);
}

}  // namespace mvr
